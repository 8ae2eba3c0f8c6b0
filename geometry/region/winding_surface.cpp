#include "geometry/region/winding_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "geometry/base/errors.h"

namespace windplan {

WindingSurface extract_winding_surface(const Mesh& full, const std::vector<char>& keep,
                                       const SpindleAxis& axis) {
  if (static_cast<int>(keep.size()) != full.num_faces()) {
    throw InputError("winding surface: face selection has " + std::to_string(keep.size()) +
                     " flags for " + std::to_string(full.num_faces()) + " faces");
  }
  WindingSurface ws;
  std::vector<int> new_index(full.num_vertices(), -1);
  TriangleSoup soup;
  for (int f = 0; f < full.num_faces(); ++f) {
    if (!keep[f]) continue;
    Tri t = full.triangle(f);
    for (int& v : t) {
      if (new_index[v] < 0) {
        new_index[v] = static_cast<int>(soup.points.size());
        soup.points.push_back(full.position(v));
        ws.vertex_map.push_back(v);
      }
      v = new_index[v];
    }
    soup.triangles.push_back(t);
    ws.face_map.push_back(f);
  }
  if (soup.triangles.empty()) {
    throw TopologyError(
        "winding surface is empty: no face of the mandrel is in the wound region "
        "(0 components, 0 boundary loops; an annulus needs 1 and 2)");
  }
  ws.mesh = Mesh(std::move(soup));
  const int components = ws.mesh.num_components();
  const auto loops = ws.mesh.boundary_loops();
  const int genus = components == 1 ? ws.mesh.genus() : -1;
  if (components != 1 || loops.size() != 2 || genus != 0) {
    throw TopologyError("winding surface is not an annulus: it has " + std::to_string(components) +
                        " component(s) and " + std::to_string(loops.size()) + " boundary loop(s)" +
                        (components == 1 ? " (genus " + std::to_string(genus) + ")" : "") +
                        "; an annulus has 1 component, 2 loops, genus 0");
  }
  for (int i = 0; i < 2; ++i) {
    WindingLoop& L = ws.loops[i];
    L.vertices = ws.mesh.loop_vertices(loops[i]);
    const int n = static_cast<int>(L.vertices.size());
    for (int k = 0; k < n; ++k) {
      const Vec3& p = ws.mesh.position(L.vertices[k]);
      L.length += (ws.mesh.position(L.vertices[(k + 1) % n]) - p).norm();
      L.mean_radius += axis.radius(p);
      L.axial += axis.axial(p);
    }
    L.mean_radius /= n;
    L.axial /= n;
  }
  if (ws.loops[1].axial < ws.loops[0].axial) std::swap(ws.loops[0], ws.loops[1]);
  ws.area = ws.mesh.total_area();
  return ws;
}

bool AxisInferenceOptions::is_valid(std::string* why) const {
  if (slices < 2 || sectors < 3 || !(revolution_tolerance > 0.0)) {
    if (why) *why = "axis inference needs slices >= 2, sectors >= 3, revolution_tolerance > 0";
    return false;
  }
  return true;
}

double radius_spread(const Mesh& mesh, const SpindleAxis& axis,
                     const AxisInferenceOptions& options) {
  // Cut the mesh by `slices` planes normal to the axis (at the middles of equal axial slices, so
  // never at an end cap): on a surface of revolution the edge crossings of a plane lie on circles
  // about the axis, up to the chord sagitta of the tessellation.
  double amin = std::numeric_limits<double>::infinity(), amax = -amin, rmax = 0.0;
  for (const Vec3& p : mesh.points()) {
    amin = std::min(amin, axis.axial(p));
    amax = std::max(amax, axis.axial(p));
    rmax = std::max(rmax, axis.radius(p));
  }
  if (!(rmax > 0.0) || !(amax > amin)) return 0.0;
  const int S = options.slices, K = options.sectors;
  const double h = (amax - amin) / S;
  const Vec3 d = axis.direction.normalized();
  const Vec3 u = d.unitOrthogonal(), w = d.cross(u);
  const double inf = std::numeric_limits<double>::infinity();
  // Per plane and angular sector: the smallest and largest crossing radius. A torus has two
  // sheets per plane, so compare sectors with each other rather than crossings.
  std::vector<double> lo(static_cast<std::size_t>(S) * K, inf), hi(lo.size(), -1.0);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int he = mesh.edge_halfedge(e);
    const Vec3& p = mesh.position(mesh.from(he));
    const Vec3& q = mesh.position(mesh.to(he));
    const double ap = axis.axial(p), aq = axis.axial(q);
    if (std::abs(aq - ap) < 1e-12) continue;
    // Planes i at amin + (i + 0.5) h with min(ap, aq) <= plane <= max(ap, aq).
    const int i0 = static_cast<int>(std::ceil((std::min(ap, aq) - amin) / h - 0.5));
    const int i1 = static_cast<int>(std::floor((std::max(ap, aq) - amin) / h - 0.5));
    for (int i = std::max(i0, 0); i <= std::min(i1, S - 1); ++i) {
      const double t = (amin + (i + 0.5) * h - ap) / (aq - ap);
      const Vec3 x = p + t * (q - p) - axis.origin;
      const double ang = std::atan2(x.dot(w), x.dot(u));
      const int k = std::clamp(static_cast<int>((ang + M_PI) / (2.0 * M_PI) * K), 0, K - 1);
      const double r = axis.radius(x + axis.origin);
      const std::size_t c = static_cast<std::size_t>(i) * K + k;
      lo[c] = std::min(lo[c], r);
      hi[c] = std::max(hi[c], r);
    }
  }
  double worst = 0.0;
  for (int i = 0; i < S; ++i) {
    double lo_min = inf, lo_max = -inf, hi_min = inf, hi_max = -inf;
    int filled = 0;
    for (int k = 0; k < K; ++k) {
      const std::size_t c = static_cast<std::size_t>(i) * K + k;
      if (hi[c] < 0.0) continue;
      ++filled;
      lo_min = std::min(lo_min, lo[c]);
      lo_max = std::max(lo_max, lo[c]);
      hi_min = std::min(hi_min, hi[c]);
      hi_max = std::max(hi_max, hi[c]);
    }
    if (filled >= 2) worst = std::max({worst, (lo_max - lo_min) / rmax, (hi_max - hi_min) / rmax});
  }
  return worst;
}

AxisInference infer_spindle_axis(const Mesh& mesh, const AxisInferenceOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError(why);
  if (mesh.num_faces() == 0) throw InputError("axis inference: the mesh has no faces");
  // Area centroid and second moment about it. For a triangle (a, b, c) of area A,
  // int x x^T dA = A / 12 (sum_i v_i v_i^T + s s^T), s = a + b + c (exact for linear triangles).
  double area = 0.0;
  Vec3 centroid = Vec3::Zero();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double a = mesh.face_area(f);
    area += a;
    centroid += a * mesh.face_centroid(f);
  }
  if (!(area > 0.0)) throw InputError("axis inference: the mesh has zero area");
  centroid /= area;
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Tri& t = mesh.triangle(f);
    const Vec3 a = mesh.position(t[0]) - centroid, b = mesh.position(t[1]) - centroid,
               c = mesh.position(t[2]) - centroid;
    const Vec3 s = a + b + c;
    C += mesh.face_area(f) / 12.0 *
         (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
  const Vec3 l = eig.eigenvalues();  // ascending
  AxisInference out;
  out.moments = l;
  // Two candidates: the distinct moment (revolution) and the largest extent (elongated shapes).
  const int distinct = (l(1) - l(0) < l(2) - l(1)) ? 2 : 0;
  auto canonical = [](Vec3 d) {
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d(k)) < 1e-12) d(k) = 0.0;  // no "-0" in reports
    }
    int i;
    d.cwiseAbs().maxCoeff(&i);
    return d(i) < 0.0 ? Vec3(-d) : d;
  };
  SpindleAxis axis;
  axis.origin = centroid;
  axis.direction = canonical(eig.eigenvectors().col(distinct).normalized());
  out.radius_spread = radius_spread(mesh, axis, options);
  if (out.radius_spread <= options.revolution_tolerance) {
    out.axis = axis;
    out.revolution = true;
    out.method = "revolution axis";
    return out;
  }
  axis.direction = canonical(eig.eigenvectors().col(2).normalized());
  out.axis = axis;
  out.radius_spread = radius_spread(mesh, axis, options);
  out.revolution = out.radius_spread <= options.revolution_tolerance;
  out.method = out.revolution ? "revolution axis" : "principal axis (not a surface of revolution)";
  return out;
}

RadiusProfile compute_radius_profile(const Mesh& mesh, const SpindleAxis& axis, int stations,
                                     bool bound_between) {
  RadiusProfile prof;
  if (mesh.num_vertices() == 0 || stations < 1) return prof;
  double amin = std::numeric_limits<double>::infinity(), amax = -amin;
  for (const Vec3& p : mesh.points()) {
    amin = std::min(amin, axis.axial(p));
    amax = std::max(amax, axis.axial(p));
  }
  if (!(amax > amin)) {
    double r = 0.0;
    for (const Vec3& p : mesh.points()) r = std::max(r, axis.radius(p));
    prof.axial = {amin};
    prof.radius = {r};
    return prof;
  }
  const double h = (amax - amin) / stations;
  std::vector<double> best(stations + 1, 0.0);
  for (const Vec3& p : mesh.points()) {
    const int i =
        std::clamp(static_cast<int>(std::lround((axis.axial(p) - amin) / h)), 0, stations);
    best[i] = std::max(best[i], axis.radius(p));
  }
  // Edges crossing station planes (long triangles of a coarse cylinder have no vertex there).
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int he = mesh.edge_halfedge(e);
    const Vec3& p = mesh.position(mesh.from(he));
    const Vec3& q = mesh.position(mesh.to(he));
    double ap = axis.axial(p), aq = axis.axial(q);
    if (std::abs(aq - ap) < 1e-12) continue;
    const int i0 = static_cast<int>(std::ceil((std::min(ap, aq) - amin) / h));
    const int i1 = static_cast<int>(std::floor((std::max(ap, aq) - amin) / h));
    for (int i = std::max(i0, 0); i <= std::min(i1, stations); ++i) {
      const double t = (amin + i * h - ap) / (aq - ap);
      best[i] = std::max(best[i], axis.radius(p + t * (q - p)));
    }
  }
  if (bound_between) {
    // The largest radius over each interval [i, i + 1]: its vertices and its end planes' crossings.
    std::vector<double> span(stations, 0.0);
    for (int i = 0; i < stations; ++i) span[i] = std::max(best[i], best[i + 1]);
    for (const Vec3& p : mesh.points()) {
      const int i =
          std::clamp(static_cast<int>(std::floor((axis.axial(p) - amin) / h)), 0, stations - 1);
      span[i] = std::max(span[i], axis.radius(p));
    }
    for (int i = 0; i <= stations; ++i) {
      best[i] = std::max(i > 0 ? span[i - 1] : 0.0, i < stations ? span[i] : 0.0);
    }
  }
  for (int i = 0; i <= stations; ++i) {
    prof.axial.push_back(amin + i * h);
    prof.radius.push_back(best[i]);
  }
  return prof;
}

}  // namespace windplan
