#pragma once
// Per-face weighting of path length (Liu et al., eq. 3-6).
//
//  - Euclidean:   cost of a segment w inside face f is |w|.
//  - Density:     rho_f |w|, rho_f > 0 per face (eq. 3).
//  - Anisotropic: |T_f u| where u = (w . e1, w . e2) are the segment's coordinates in the face
//                 frame and T_f = [[a, b], [b, c]] is symmetric positive definite (eq. 5).
//                 Face frame: e1 = (p1 - p0) / |p1 - p0|, e2 = n x e1, with (p0, p1, p2) the
//                 face's corners in Mesh::triangle(f) order and n its unit normal.
//
// Every kind is evaluated as sqrt(w^T G_f w) with G_f = I, rho_f^2 I or E T_f^2 E^T
// (E = [e1 e2]); the per-face G_f is precomputed once.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "geometry/mesh/mesh.h"

namespace windplan {

class PathMetric {
 public:
  enum class Kind { Euclidean, Density, Anisotropic };

  /// The Euclidean metric.
  PathMetric() = default;
  /// Density metric. \throw InputError naming the face if a value is <= 0 or not finite, or if
  /// the count differs from the mesh's face count.
  static PathMetric density(const Mesh& mesh, std::vector<double> rho);
  /// Anisotropic metric from (a, b, c) per face. \throw InputError naming the face if a matrix
  /// is not symmetric positive definite or not finite, or if the count is wrong.
  static PathMetric anisotropic(const Mesh& mesh, const std::vector<std::array<double, 3>>& abc);

  Kind kind() const { return kind_; }
  const std::vector<double>& densities() const { return rho_; }

  /// Cost sqrt(w^T G_f w) of segment w in face f.
  double cost(int f, const Vec3& w) const {
    switch (kind_) {
      case Kind::Euclidean:
        return w.norm();
      case Kind::Density:
        return rho_[f] * w.norm();
      case Kind::Anisotropic:
        return std::sqrt(std::max(0.0, w.dot(apply(f, w))));
    }
    return 0.0;
  }
  /// G_f w.
  Vec3 apply(int f, const Vec3& w) const {
    switch (kind_) {
      case Kind::Euclidean:
        return w;
      case Kind::Density:
        return (rho_[f] * rho_[f]) * w;
      case Kind::Anisotropic: {
        const double* g = &g_[6 * static_cast<std::size_t>(f)];
        return Vec3(g[0] * w.x() + g[1] * w.y() + g[2] * w.z(),
                    g[1] * w.x() + g[3] * w.y() + g[4] * w.z(),
                    g[2] * w.x() + g[4] * w.y() + g[5] * w.z());
      }
    }
    return w;
  }
  /// u^T G_f v.
  double inner(int f, const Vec3& u, const Vec3& v) const { return u.dot(apply(f, v)); }

 private:
  Kind kind_ = Kind::Euclidean;
  std::vector<double> rho_;  // Density
  std::vector<double> g_;    // Anisotropic: 6 entries (xx, xy, xz, yy, yz, zz) per face
};

/// The tangent frame (e1, e2) of face f used by the anisotropic metric.
void face_frame(const Mesh& mesh, int f, Vec3* e1, Vec3* e2);

}  // namespace windplan
