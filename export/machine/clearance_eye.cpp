#include "export/machine/clearance_eye.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "geometry/base/errors.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

namespace {

// The pseudo-normal of the closest feature of a face point (zero on an open boundary).
Vec3 closest_side_normal(const Mesh& mesh, const SurfacePoint& sp) {
  const int f = containing_face(mesh, sp);
  const Vec3 b = barycentric_in_face(mesh, f, sp);
  constexpr double eps = 1e-9;
  int zeros = 0, nonzero = -1;
  for (int k = 0; k < 3; ++k) {
    if (b[k] <= eps) {
      ++zeros;
    } else {
      nonzero = k;
    }
  }
  if (zeros == 0) return mesh.face_normal(f);
  if (zeros == 1) {
    int k = 0;
    while (b[k] > eps) ++k;
    const int he = 3 * f + (k + 1) % 3;  // the edge opposite corner k
    const int tw = mesh.twin(he);
    if (mesh.is_boundary_halfedge(tw)) return Vec3::Zero();
    return (mesh.face_normal(f) + mesh.face_normal(mesh.face(tw))).normalized();
  }
  const int v = mesh.triangle(f)[nonzero];
  if (mesh.is_boundary_vertex(v)) return Vec3::Zero();
  return mesh.vertex_normal(v);
}

}  // namespace

ClearanceEye solve_clearance_eye(const Mesh& mesh, const ClosestPointQuery& query, const Vec3& p,
                                 const Vec3& t_in, double clearance, const std::string& where,
                                 double tolerance, double max_length) {
  const std::string at = where.empty() ? std::string() : where + ": ";
  const double tn = t_in.norm();
  if (!(tn > 1e-12) || !std::isfinite(tn)) {
    throw InputError(at + "the fibre tangent is zero or not finite");
  }
  if (!p.allFinite()) throw InputError(at + "the fibre point is not finite");
  const Vec3 t = t_in / tn;
  ClearanceEye s;
  // Distance from E(l) to the mesh, and whether E(l) is inside the mandrel: below the plane of its
  // closest face (the mesh's faces are oriented outwards) by more than 1e-3 mm.
  // The side is read from the closest feature's angle-weighted pseudo-normal (Baerentzen and
  // Aanaes): a face's normal, an edge's two faces, a vertex's fan weighted by its angles; a point
  // whose closest feature lies on an open boundary (beyond a region's cut end) is outside.
  bool inside = false;
  auto dist = [&](double l) {
    const Vec3 e = p + l * t;
    const ClosestPointQuery::Hit h = query.closest(e);
    ++s.iterations;
    inside = false;
    if (h.distance > 1e-3 && h.point.element >= 0) {
      const Vec3 n = closest_side_normal(mesh, h.point);
      inside = n.allFinite() && n.squaredNorm() > 0.0 && (e - h.position).dot(n) < -1e-3;
    }
    return h.distance;
  };
  double lo = 0.0, hi = 0.0, d = 0.0;
  bool was_inside = false;
  while (true) {
    // Outside, d is 1-Lipschitz in l: no l in (hi, hi + clearance - d) reaches the clearance.
    // Inside (the line cut into the mandrel), the ball of radius d is inside: step by d to the
    // way out, then on as outside.
    const double step = std::max(was_inside ? d : clearance - d, tolerance);
    lo = hi;
    hi += step;
    d = dist(hi);
    was_inside = inside;
    if (inside) s.enters = true;
    if (!inside && d >= clearance) break;
    if (hi > max_length) {
      char buf[120];
      std::snprintf(buf, sizeof buf,
                    "the fibre tangent stays within the clearance %.6g mm of the mandrel for "
                    "%.6g mm",
                    clearance, max_length);
      throw InputError(at + buf);
    }
  }
  // Only whether a point is nearer than the clearance matters here: a query bounded just above
  // it prunes the far parts of the mesh, and when it finds a point, that is closest()'s hit.
  const double bound = clearance * (1.0 + 1e-9) + 1e-9;
  auto nearer_than_clearance = [&](double l) {
    const ClosestPointQuery::Hit h = query.closest_within(p + l * t, bound * bound);
    ++s.iterations;
    return h.point.element >= 0 && h.distance < clearance;
  };
  while (hi - lo > tolerance) {
    const double mid = 0.5 * (lo + hi);
    if (nearer_than_clearance(mid)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  // The eye at hi: at or just beyond the clearance.
  s.free_length = hi;
  s.eye = p + hi * t;
  s.distance = query.closest(s.eye).distance;
  return s;
}

}  // namespace windplan
