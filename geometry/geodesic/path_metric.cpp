#include "geometry/geodesic/path_metric.h"

#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "geometry/base/errors.h"

namespace windplan {

void face_frame(const Mesh& mesh, int f, Vec3* e1, Vec3* e2) {
  const Tri& t = mesh.triangle(f);
  *e1 = (mesh.position(t[1]) - mesh.position(t[0])).normalized();
  *e2 = mesh.face_normal(f).cross(*e1);
}

PathMetric PathMetric::density(const Mesh& mesh, std::vector<double> rho) {
  if (static_cast<int>(rho.size()) != mesh.num_faces()) {
    throw InputError("density: " + std::to_string(rho.size()) + " values for " +
                     std::to_string(mesh.num_faces()) + " faces (one value per face)");
  }
  for (std::size_t f = 0; f < rho.size(); ++f) {
    if (!std::isfinite(rho[f]) || rho[f] <= 0.0) {
      std::ostringstream s;
      s << "density of face " << f << " is " << rho[f] << ": it must be finite and > 0";
      throw InputError(s.str());
    }
  }
  PathMetric m;
  m.kind_ = Kind::Density;
  m.rho_ = std::move(rho);
  return m;
}

PathMetric PathMetric::anisotropic(const Mesh& mesh,
                                   const std::vector<std::array<double, 3>>& abc) {
  if (static_cast<int>(abc.size()) != mesh.num_faces()) {
    throw InputError("metric: " + std::to_string(abc.size()) + " tensors for " +
                     std::to_string(mesh.num_faces()) + " faces (one a,b,c triple per face)");
  }
  PathMetric m;
  m.kind_ = Kind::Anisotropic;
  m.g_.resize(6 * abc.size());
  for (std::size_t f = 0; f < abc.size(); ++f) {
    const double a = abc[f][0], b = abc[f][1], c = abc[f][2];
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c) || a <= 0.0 ||
        a * c - b * b <= 0.0) {
      std::ostringstream s;
      s << "metric of face " << f << " [[" << a << ", " << b << "], [" << b << ", " << c
        << "]] is not symmetric positive definite";
      throw InputError(s.str());
    }
    Eigen::Matrix2d T;
    T << a, b, b, c;
    const Eigen::Matrix2d T2 = T * T;
    Vec3 e1, e2;
    face_frame(mesh, static_cast<int>(f), &e1, &e2);
    Eigen::Matrix<double, 3, 2> E;
    E.col(0) = e1;
    E.col(1) = e2;
    const Eigen::Matrix3d G = E * T2 * E.transpose();
    double* g = &m.g_[6 * f];
    g[0] = G(0, 0);
    g[1] = G(0, 1);
    g[2] = G(0, 2);
    g[3] = G(1, 1);
    g[4] = G(1, 2);
    g[5] = G(2, 2);
  }
  return m;
}

}  // namespace windplan
