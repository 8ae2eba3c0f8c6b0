#include "geometry/region/plane_section.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

std::string vec_str(const Vec3& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

// Signed turns of a closed polygon around the axis (projected onto the plane normal to it).
int winding_number(const std::vector<Vec3>& pts, const SpindleAxis& axis) {
  if (pts.size() < 3) return 0;
  const Vec3 a = axis.direction.normalized();
  const Vec3 e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  double total = 0.0;
  auto angle = [&](const Vec3& p) {
    const Vec3 d = p - axis.origin;
    return std::atan2(d.dot(e2), d.dot(e1));
  };
  double prev = angle(pts.back());
  for (const Vec3& p : pts) {
    const double cur = angle(p);
    double da = cur - prev;
    while (da > M_PI) da -= 2.0 * M_PI;
    while (da < -M_PI) da += 2.0 * M_PI;
    total += da;
    prev = cur;
  }
  return static_cast<int>(std::lround(total / (2.0 * M_PI)));
}

}  // namespace

double polyline_length(const std::vector<Vec3>& pts, bool closed) {
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  if (closed && pts.size() > 1) len += (pts.front() - pts.back()).norm();
  return len;
}

// Plane sections of one mesh, with the precomputed data that tells whether a closed section loop
// goes around the mandrel: on an annulus (two boundary loops) the edges of one edge path from the
// first boundary loop to the second; a simple closed loop separates the two boundaries (is not
// contractible) exactly when it crosses that path an odd number of times. Other meshes (closed
// or with other boundaries) use the winding number around the axis.
PlaneSectioner::PlaneSectioner(const Mesh& mesh, const SpindleAxis& axis)
    : mesh_(mesh), axis_(axis) {
  const auto loops = mesh.boundary_loops();
  if (loops.size() != 2) return;
  const int nv = mesh.num_vertices();
  std::vector<std::vector<int>> adj(nv);
  for (int h = 0; h < mesh.num_interior_halfedges(); ++h) {
    adj[mesh.from(h)].push_back(h);
    adj[mesh.to(h)].push_back(h);
  }
  std::vector<int> via(nv, -2);  // -2 unseen, -1 source, else the halfedge reached through
  std::vector<char> target(nv, 0);
  std::vector<int> queue;
  for (int v : mesh.loop_vertices(loops[0])) via[v] = -1, queue.push_back(v);
  for (int v : mesh.loop_vertices(loops[1])) target[v] = 1;
  int hit = -1;
  for (std::size_t q = 0; q < queue.size() && hit < 0; ++q) {
    const int v = queue[q];
    for (int h : adj[v]) {
      const int w = mesh.from(h) == v ? mesh.to(h) : mesh.from(h);
      if (via[w] != -2) continue;
      via[w] = h;
      if (target[w]) {
        hit = w;
        break;
      }
      queue.push_back(w);
    }
  }
  if (hit < 0) return;
  transversal_.assign(mesh.num_edges(), 0);
  for (int v = hit; via[v] >= 0;) {
    const int h = via[v];
    transversal_[mesh.edge(h)] = 1;
    v = mesh.from(h) == v ? mesh.to(h) : mesh.from(h);
  }
}

std::vector<PlaneSection> PlaneSectioner::sections(const Vec3& normal, double offset) const {
  const Mesh& mesh = mesh_;
  const Vec3 n = normal.normalized();
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<double> s(nv);
  for (int v = 0; v < nv; ++v) s[v] = n.dot(mesh.position(v)) - offset;
  auto pos = [&](int v) { return s[v] >= 0.0; };
  // Per face: the exit (from +, to -) and entry (from -, to +) halfedges; -1 when not cut.
  auto exit_of = [&](int f) {
    for (int k = 0; k < 3; ++k) {
      const int h = 3 * f + k;
      if (pos(mesh.from(h)) && !pos(mesh.to(h))) return h;
    }
    return -1;
  };
  auto entry_of = [&](int f) {
    for (int k = 0; k < 3; ++k) {
      const int h = 3 * f + k;
      if (!pos(mesh.from(h)) && pos(mesh.to(h))) return h;
    }
    return -1;
  };
  auto point_on = [&](int h) {
    const double sa = s[mesh.from(h)], sb = s[mesh.to(h)];
    const double t = std::clamp(sa / (sa - sb), 0.0, 1.0);
    return std::pair<double, Vec3>(
        t, (1.0 - t) * mesh.position(mesh.from(h)) + t * mesh.position(mesh.to(h)));
  };

  std::vector<char> seen(nf, 0);
  std::vector<PlaneSection> out;
  for (int f0 = 0; f0 < nf; ++f0) {
    if (seen[f0] || exit_of(f0) < 0) continue;
    // Walk backwards to the start of an open chain (or all the way round a loop).
    int first = f0;
    bool closed = true;
    for (;;) {
      const int prev = mesh.face(mesh.twin(entry_of(first)));
      if (prev < 0) {
        closed = false;
        break;
      }
      if (prev == f0) break;
      first = prev;
    }
    PlaneSection sec;
    sec.closed = closed;
    sec.path.closed = closed;
    if (!closed) sec.points.push_back(point_on(mesh.twin(entry_of(first))).second);
    int f = closed ? f0 : first;
    int crossings = 0;
    for (;;) {
      seen[f] = 1;
      const int h = exit_of(f);
      const auto [t, p] = point_on(h);
      sec.points.push_back(p);
      const int g = mesh.face(mesh.twin(h));
      if (g < 0) break;  // open chain: the last point is on the boundary
      sec.path.halfedges.push_back(h);
      sec.path.lambdas.push_back(t);
      if (!transversal_.empty()) crossings += transversal_[mesh.edge(h)];
      if (closed && g == f0) break;
      f = g;
    }
    sec.length = polyline_length(sec.points, closed);
    if (closed) {
      sec.winding = winding_number(sec.points, axis_);
      sec.around = transversal_.empty() ? sec.winding != 0 : crossings % 2 == 1;
    }
    out.push_back(std::move(sec));
  }
  return out;
}

bool PlaneSectioner::around_loop(const Vec3& n, double d, const Vec3* near, PlaneSection* out,
                                 std::vector<PlaneSection>* all) const {
  std::vector<PlaneSection> secs = sections(n, d);
  int best = -1;
  double best_key = 0.0;
  for (int i = 0; i < static_cast<int>(secs.size()); ++i) {
    if (!secs[i].around) continue;
    const double key = near ? -(centroid(secs[i].points) - *near).norm() : secs[i].length;
    if (best < 0 || key > best_key) best = i, best_key = key;
  }
  if (best >= 0 && out) *out = secs[best];
  if (all) *all = std::move(secs);
  return best >= 0;
}

Vec3 PlaneSectioner::centroid(const std::vector<Vec3>& pts) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : pts) c += p;
  return pts.empty() ? c : Vec3(c / static_cast<double>(pts.size()));
}

// The shorter piece of a section chain between two points lying on it (within tol), as a
// polyline a, crossings..., b. Empty when no chain passes through both.
std::vector<Vec3> arc_between(const std::vector<PlaneSection>& secs, const Vec3& a, const Vec3& b,
                              double tol) {
  std::vector<Vec3> best;
  double best_len = std::numeric_limits<double>::infinity();
  for (const PlaneSection& sec : secs) {
    const std::vector<Vec3>& P = sec.points;
    const int m = static_cast<int>(P.size());
    const int nseg = sec.closed ? m : m - 1;
    if (nseg < 1) continue;
    auto locate = [&](const Vec3& q, int* seg, double* t) {
      double dmin = std::numeric_limits<double>::infinity();
      for (int i = 0; i < nseg; ++i) {
        const Vec3& p0 = P[i];
        const Vec3& p1 = P[(i + 1) % m];
        const Vec3 e = p1 - p0;
        const double ee = e.squaredNorm();
        const double u = ee > 0.0 ? std::clamp((q - p0).dot(e) / ee, 0.0, 1.0) : 0.0;
        const double dist = (p0 + u * e - q).norm();
        if (dist < dmin) dmin = dist, *seg = i, *t = u;
      }
      return dmin;
    };
    int ia = 0, ib = 0;
    double ta = 0.0, tb = 0.0;
    if (locate(a, &ia, &ta) > tol || locate(b, &ib, &tb) > tol) continue;
    // Forward from (i0, t0) to (i1, t1) along the chain (cyclic when closed).
    auto forward = [&](const Vec3& q0, int i0, double t0, const Vec3& q1, int i1, double t1) {
      std::vector<Vec3> out{q0};
      if (!(i0 == i1 && t0 <= t1)) {
        for (int i = i0;;) {
          i = (i + 1) % m;
          out.push_back(P[i]);
          if (i == i1) break;
        }
      }
      out.push_back(q1);
      return out;
    };
    std::vector<std::vector<Vec3>> candidates;
    const bool a_first = ia < ib || (ia == ib && ta <= tb);
    if (sec.closed || a_first) candidates.push_back(forward(a, ia, ta, b, ib, tb));
    if (sec.closed || !a_first) {
      std::vector<Vec3> r = forward(b, ib, tb, a, ia, ta);
      std::reverse(r.begin(), r.end());
      candidates.push_back(std::move(r));
    }
    for (std::vector<Vec3>& c : candidates) {
      const double len = polyline_length(c, false);
      if (len < best_len) best_len = len, best = std::move(c);
    }
  }
  return best;
}

std::vector<PlaneSection> plane_sections(const Mesh& mesh, const Vec3& normal, double offset,
                                         const SpindleAxis& axis) {
  return PlaneSectioner(mesh, axis).sections(normal, offset);
}

PlaneSection axial_plane_section(const Mesh& mesh, const Vec3& normal, double offset,
                                 const SpindleAxis& axis, const std::string& what) {
  const PlaneSectioner S(mesh, axis);
  std::vector<PlaneSection> secs;
  PlaneSection best;
  if (S.around_loop(normal, offset, nullptr, &best, &secs)) return best;
  std::ostringstream s;
  if (secs.empty()) {
    s << what << ": the plane n = " << vec_str(normal.normalized()) << ", d = " << offset
      << " mm misses the mandrel";
    throw InputError(s.str());
  }
  int open = 0;
  for (const PlaneSection& p : secs) open += !p.closed;
  s << what << ": the section by the plane n = " << vec_str(normal.normalized())
    << ", d = " << offset << " mm does not go around the mandrel (" << secs.size() << " piece(s), "
    << open << " running into the boundary of the wound region)";
  throw InputError(s.str());
}

std::vector<Vec3> section_arc(const Mesh& mesh, const Vec3& normal, double offset, const Vec3& a,
                              const Vec3& b, double tolerance) {
  return arc_between(PlaneSectioner(mesh, SpindleAxis{}).sections(normal, offset), a, b, tolerance);
}

}  // namespace windplan
