#include "export/program/replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "export/machine/circuit_surfaces.h"
#include "export/machine/eye_envelope.h"
#include "export/machine/kinematics.h"
#include "export/machine/resample.h"
#include "export/program/polyline_track.h"
#include "geometry/base/errors.h"
#include "geometry/mesh/closest_point.h"

namespace windplan {

namespace {

constexpr double kMaxBlockTravel = 1e5;    // mm of eye travel in one block (100 m)
constexpr double kMaxBlockSubsteps = 1e6;  // sub-steps in one block

std::string format_travel(double mm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", mm);
  return buf;
}

constexpr double kPi = 3.14159265358979323846;

// The mandrel surface for the walk: closest points with normals interpolated from the face-corner
// normals (a faceted normal would make the tangency jump from edge to edge).
class Surface {
 public:
  explicit Surface(const Mesh& mesh) : mesh_(mesh), query_(mesh) {
    // Per face corner: the angle-weighted normals of the faces round the vertex that are within
    // 40 deg of this face's normal, so that a crease (a pipe's rim where the end cap meets the
    // wall) keeps two normals instead of one leaning 45 deg between them.
    const auto& tris = mesh.triangles();
    const auto& pts = mesh.points();
    const int nf = mesh.num_faces();
    std::vector<std::vector<std::pair<int, double>>> fan(mesh.num_vertices());
    std::vector<Vec3> fn(nf);
    for (int f = 0; f < nf; ++f) {
      fn[f] = mesh.face_normal(f);
      for (int k = 0; k < 3; ++k) {
        const Vec3 e1 = pts[tris[f][(k + 1) % 3]] - pts[tris[f][k]];
        const Vec3 e2 = pts[tris[f][(k + 2) % 3]] - pts[tris[f][k]];
        const double ang = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
        fan[tris[f][k]].push_back({f, ang});
      }
    }
    face_n_ = fn;
    fan_.resize(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      for (const auto& fa : fan[v]) fan_[v].push_back(fa.first);
    }
    // A flat face of the part (a rounded rectangle's side) has vertices inside it, all of whose
    // faces are coplanar; a curved surface's coarse facets (a 36-gon's strips, a cone's) have none:
    // every vertex sits on a fold. The straight-fibre rules below hold on the former only.
    std::vector<char> planar_vertex(mesh.num_vertices(), 0);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      bool planar = !fan[v].empty();
      for (const auto& fa : fan[v]) {
        planar = planar && fn[fa.first].dot(fn[fan[v].front().first]) >= 1.0 - 1e-12;
      }
      planar_vertex[v] = planar;
    }
    flat_face_.assign(nf, 0);
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) flat_face_[f] = flat_face_[f] || planar_vertex[tris[f][k]];
    }
    const double crease = std::cos(40.0 * kPi / 180.0);
    corner_.resize(static_cast<std::size_t>(nf) * 3);
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        Vec3 n = Vec3::Zero();
        for (const auto& [g, ang] : fan[tris[f][k]]) {
          if (fn[g].dot(fn[f]) >= crease) n += ang * fn[g];
        }
        corner_[3 * f + k] = n.norm() > 1e-12 ? Vec3(n.normalized()) : fn[f];
      }
    }
  }
  struct Point {
    Vec3 p = Vec3::Zero();
    Vec3 n = Vec3::UnitX();   ///< interpolated normal (the walk's tangency)
    Vec3 fn = Vec3::UnitX();  ///< the facet's normal (flat faces: the face's plane)
    bool flat = false;        ///< the facet has a vertex all of whose faces are coplanar with it
  };
  /// The closest point with its interpolated normal. On a crease (an edge or vertex shared by
  /// faces more than 40 deg apart, e.g. a tube's rim) the face whose normal is closest to `ref`
  /// (the walking contact's normal) is taken, so that the walk stays on its side of the crease.
  /// `within` (mm): a surface point is known to lie within it of q (the query then prunes far
  /// parts of the mesh early and gives the same hit).
  Point project(const Vec3& q, const Vec3* ref = nullptr,
                double within = std::numeric_limits<double>::infinity()) const {
    ClosestPointQuery::Hit h = query_.closest_within(q, within * within);
    if (h.point.element < 0) h = query_.closest(q);
    Point out;
    out.p = h.position;
    int f = containing_face(mesh_, h.point);
    if (ref && h.point.kind != SurfacePoint::Kind::Face) {
      // Faces round the triangle's vertex nearest to the hit.
      const auto& t0 = mesh_.triangles()[f];
      int v = t0[0];
      for (int k = 1; k < 3; ++k) {
        if ((mesh_.points()[t0[k]] - h.position).squaredNorm() <
            (mesh_.points()[v] - h.position).squaredNorm()) {
          v = t0[k];
        }
      }
      double best = face_n_[f].dot(*ref);
      for (int g : fan_[v]) {
        const auto& tg = mesh_.triangles()[g];
        Vec3 bg;
        const Vec3 pg = closest_point_on_triangle(
            h.position, mesh_.points()[tg[0]], mesh_.points()[tg[1]], mesh_.points()[tg[2]], &bg);
        if ((pg - h.position).norm() > 1e-6) continue;  // the hit is not on this face
        if (face_n_[g].dot(*ref) > best) {
          best = face_n_[g].dot(*ref);
          f = g;
        }
      }
    }
    const auto& t = mesh_.triangles()[f];
    Vec3 bary = h.point.bary;
    if (h.point.kind != SurfacePoint::Kind::Face || f != h.point.element) {
      // Barycentric coordinates of the hit in face f.
      closest_point_on_triangle(h.position, mesh_.points()[t[0]], mesh_.points()[t[1]],
                                mesh_.points()[t[2]], &bary);
    }
    Vec3 n = bary[0] * corner_[3 * f] + bary[1] * corner_[3 * f + 1] + bary[2] * corner_[3 * f + 2];
    const double nn = n.norm();
    out.n = nn > 0.0 ? Vec3(n / nn) : mesh_.face_normal(f);
    out.fn = face_n_[f];
    out.flat = flat_face_[f];
    return out;
  }

  double distance(const Vec3& q) const { return query_.closest(q).distance; }

 private:
  const Mesh& mesh_;
  ClosestPointQuery query_;
  std::vector<Vec3> corner_;
  std::vector<Vec3> face_n_;
  std::vector<std::vector<int>> fan_;
  std::vector<char> flat_face_;
};

double lift(const Surface::Point& p, const Vec3& eye) { return (eye - p.p).dot(p.n); }

// Advances the contact point P towards the eye until the free fibre is tangent (header comment).
// The lift (E - P(h)) . n(P(h)) along the walk P(h) = proj(P + h dir) is bracketed starting from
// the previous step's walk length *h_guess, then its root found by regula falsi (Illinois).
void advance(const Surface& surf, const Vec3& eye, Surface::Point* P, double* h_guess,
             double max_walk) {
  double walked = 0.0;
  for (int round = 0; round < 16 && walked < max_walk; ++round) {
    const Vec3 d = eye - P->p;
    const double len = d.norm();
    const double f0 = lift(*P, eye);
    if (!(len > 0.0) || f0 >= -1e-12 * len) return;
    const Vec3 w = d - d.dot(P->n) * P->n;
    const double wn = std::min(w.norm(), max_walk - walked);
    if (!(wn > 1e-12)) return;
    const Vec3 dir = w.normalized();
    const Vec3 ref = P->n;
    // P is on the surface, |h dir| from the point projected.
    auto at = [&](double h) {
      return surf.project(P->p + h * dir, &ref, std::abs(h) * (1.0 + 1e-9) + 1e-9);
    };
    double h_lo = 0.0, f_lo = f0;
    Surface::Point lo = *P, hi;
    double h = std::clamp(*h_guess, 1e-4, wn), f_hi = 0.0;
    bool found = false;
    while (true) {
      const Surface::Point q = at(h);
      const double f = lift(q, eye);
      if (f >= 0.0) {
        hi = q;
        f_hi = f;
        found = true;
        break;
      }
      lo = q;
      h_lo = h;
      f_lo = f;
      if (h >= wn) break;
      h = std::min(2.0 * h, wn);
    }
    if (!found) {
      *P = lo;  // not tangent within reach: go as far as that and aim again
      walked += h_lo;
      continue;
    }
    double h_hi = h;
    int side = 0;
    for (int it = 0; it < 40 && h_hi - h_lo > 1e-6; ++it) {
      double mid = (h_lo * f_hi - h_hi * f_lo) / (f_hi - f_lo);
      if (!(mid > h_lo && mid < h_hi)) mid = 0.5 * (h_lo + h_hi);
      const Surface::Point q = at(mid);
      const double f = lift(q, eye);
      if (f >= 0.0) {
        h_hi = mid;
        f_hi = f;
        hi = q;
        if (side == 1) f_lo *= 0.5;
        side = 1;
      } else {
        h_lo = mid;
        f_lo = f;
        lo = q;
        if (side == -1) f_hi *= 0.5;
        side = -1;
      }
      if (std::fabs(f) < 1e-9) break;
    }
    *h_guess = std::max(1e-4, h_hi);
    *P = hi;
    return;
  }
}

// A fibre is straight where the surface is flat, so on a flat face the contact walk has nothing
// to find: with the eye in the face's plane every point of it is "tangent" ((E - P) . n = 0), and
// with the eye below that plane the lift is the same negative number all across the face. Both
// cases lay a straight fibre on the face, and the contact is where that fibre leaves it:
//  - lift >= 0: the free fibre P -> E itself; the contact moves along it while it lies on the face;
//  - lift < 0: the fibre wraps on along the tangent-plane direction of E - P, straight while the
//    surface under it is flat (where it curves, advance() takes over).
// The straight line is probed every `probe` mm from P; a probe point within `touch` of the surface
// lies on it (a curved surface of radius R falls away by probe^2 / 2R: 0.016 mm at R = 128 mm and
// 2 mm, so only a face flat to `touch` over the probe passes). It stops at the first point within
// `catch_distance` of a held point (the pins take the fibre there). Returns the length laid, mm.
double lay_straight(const Surface& surf, const Vec3& eye, Surface::Point* P, double probe,
                    double touch, const Vec3* pin, double catch_distance) {
  if (!(touch > 0.0)) return 0.0;
  Vec3 d = eye - P->p;
  const double len = d.norm();
  if (!(len > probe)) return 0.0;
  const Vec3 n0 = P->fn;
  if (d.dot(n0) < 0.0) d -= d.dot(n0) * n0;
  const double reach = d.norm();
  if (!(reach > probe)) return 0.0;
  const Vec3 w = d / reach;
  const Vec3 p0 = P->p;
  // A point on the plane of the face: within touch of it, on a facet of the same normal.
  auto on_plane = [&](const Vec3& q, Surface::Point* Q) {
    *Q = surf.project(q, &P->n);
    return Q->flat && (q - Q->p).norm() <= touch && Q->fn.dot(n0) >= 1.0 - 1e-9;
  };
  // A face, not a facet strip: the plane reaches probe / 2 to one side of the fibre too (a
  // cylinder's facets are straight along its axis; 0.6 mm wide on the shipped pipe's mesh).
  const Vec3 side = 0.5 * probe * n0.cross(w);
  double laid = 0.0;
  for (double s = probe; s < reach; s += probe) {
    const Vec3 q = p0 + s * w;
    Surface::Point Q, Qs;
    if (!on_plane(q, &Q) || !(on_plane(q + side, &Qs) || on_plane(q - side, &Qs))) break;
    *P = Q;
    laid = s;
    if (pin && (Q.p - *pin).norm() <= catch_distance) break;
  }
  return laid;
}

int reversals(const std::vector<double>& v) {
  int count = 0, dir = 0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double d = v[i] - v[i - 1];
    if (std::fabs(d) < 1e-9) continue;
    const int s = d > 0 ? 1 : -1;
    if (dir != 0 && s != dir) ++count;
    dir = s;
  }
  return count;
}

}  // namespace

ReplayResult replay_program(const GcodeProgram& program, const WindingPlan& plan,
                            const Mesh& mandrel, const MachineOptions& machine,
                            const ReplayOptions& options,
                            const std::vector<const Mesh*>& circuit_surfaces) {
  const auto t0 = std::chrono::steady_clock::now();
  if (machine.kind == "robot") throw InputError("machine.kind: robot has no G-code to replay");
  if (program.blocks.empty()) throw InputError("the program has no moves");
  if (mandrel.num_faces() == 0) throw InputError("the mandrel mesh is empty");
  std::vector<Vec3> planned, planned_n;
  std::vector<int> circuit_start;  // index of each circuit's first point in `planned`
  std::vector<int> start_mesh;     // the surface (entry of surfaces_of.meshes) of the circuit there
  std::vector<char> held;          // on a turnaround: a pin ring or boss holds the fibre there
  std::vector<int> tie_on;         // index in `planned` of each later layer's first point, sorted
  const CircuitSurfaces surfaces_of = distinct_circuit_surfaces(plan, mandrel, circuit_surfaces);
  const std::vector<char> starts_layer = layer_start_circuits(plan);
  for (std::size_t ci = 0; ci < plan.circuits.size(); ++ci) {
    const Circuit& c = plan.circuits[ci];
    if (starts_layer[ci] && !planned.empty()) tie_on.push_back(static_cast<int>(planned.size()));
    std::vector<char> on_turn(c.points.size(), 0);
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind != CircuitSegment::Kind::Turnaround) continue;
      for (int i = std::max(0, seg.first); i <= seg.last && i < static_cast<int>(on_turn.size());
           ++i) {
        on_turn[i] = 1;
      }
    }
    if (!c.points.empty()) {
      circuit_start.push_back(static_cast<int>(planned.size()));
      start_mesh.push_back(surfaces_of.of[ci]);
    }
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const FibrePoint& p = c.points[i];
      if (planned.empty() || (p.position - planned.back()).norm() > 1e-12) {
        planned.push_back(p.position);
        planned_n.push_back(p.normal);
        held.push_back(on_turn[i]);
      } else {
        held.back() = held.back() || on_turn[i];
      }
    }
  }
  if (planned.empty()) throw InputError("the plan has no fibre points");
  std::vector<double> planned_s(planned.size(), 0.0);
  for (std::size_t i = 1; i < planned.size(); ++i) {
    planned_s[i] = planned_s[i - 1] + (planned[i] - planned[i - 1]).norm();
  }
  // Per turnaround point, the sense in which its arc turns about the surface normal (+1 left,
  // -1 right, 0 not held): the side of the pins' bend, for a fibre turned in a flat face's plane.
  std::vector<signed char> bend(planned.size(), 0);
  for (std::size_t i = 0; i < planned.size();) {
    if (!held[i]) {
      ++i;
      continue;
    }
    std::size_t k = i;
    double turn = 0.0;
    while (k + 1 < planned.size() && held[k + 1]) ++k;
    for (std::size_t m = i + 1; m + 1 <= k && m + 1 < planned.size(); ++m) {
      turn += planned_n[m].dot((planned[m] - planned[m - 1]).cross(planned[m + 1] - planned[m]));
    }
    // The pass leaving the arc turns with it too (its first point after the last pin).
    if (k + 1 < planned.size() && k > i) {
      turn += planned_n[k].dot((planned[k] - planned[k - 1]).cross(planned[k + 1] - planned[k]));
    }
    for (std::size_t m = i; m <= k; ++m) bend[m] = turn > 0.0 ? 1 : (turn < 0.0 ? -1 : 0);
    i = k + 1;
  }
  // Per planned point, the first and last points of its layer (the tow is cut at a layer's end
  // and tied on again at the next layer's first point by a rapid, below): the contact, the pins
  // that catch it and the deviation's track stay between them. Without the last, the robot
  // replay of pipe_robot_layup with its eyes 0.05 mm further out let the pins of the second
  // layer's first circuit catch the contact at the first layer's end, and its rapid then tied the
  // tow on at the second layer's second circuit: 15.98 mm off. Without the first, the track at a
  // tie-on reached one segment back (the step between the layers), took it for the nearest and
  // put the contact back on the previous layer's last turnaround: a hoop's tie-on turn on the
  // taper of the helical layer under it replayed 4.11 mm off in the KR 16 cell (now 0.231).
  std::vector<char> is_tie_on(planned.size() + 1, 0);
  for (int t : tie_on) is_tie_on[t] = 1;
  std::vector<int> stretch_last(planned.size(), static_cast<int>(planned.size()) - 1);
  std::vector<int> stretch_first(planned.size(), 0);  // and its layer's first point
  for (int i = static_cast<int>(planned.size()) - 2; i >= 0; --i) {
    stretch_last[i] = is_tie_on[i + 1] ? i : stretch_last[i + 1];
  }
  for (std::size_t i = 1; i < planned.size(); ++i) {
    stretch_first[i] = is_tie_on[i] ? static_cast<int>(i) : stretch_first[i - 1];
  }
  // The first turnaround point at or after each planned point in its stretch (-1: none).
  std::vector<int> next_held(planned.size(), -1);
  for (int i = static_cast<int>(planned.size()) - 1; i >= 0; --i) {
    next_held[i] = held[i] ? i : (i < stretch_last[i] ? next_held[i + 1] : -1);
  }
  const bool lathe2 = machine.kind == "lathe2";
  const AxisFrame frame = make_axis_frame(plan.axis);
  double eye_radius = 0.0;
  if (lathe2) {
    eye_radius = make_envelope(swept_profile(plan, &mandrel), machine.envelope, "lathe2").r.front();
  }
  // y: the eye's radius (lathe2: its cylinder's, set by hand at the last operator stop, or the
  // machine's own before any).
  auto eye_at = [&](double a_deg, double x, double y) {
    const double th = -a_deg * kPi / 180.0;
    return Vec3(frame.origin + x * frame.d + y * (std::cos(th) * frame.u + std::sin(th) * frame.v));
  };

  // One walking surface per distinct mesh; `surf` is the one under the circuit at ptr.
  std::vector<std::unique_ptr<const Surface>> surfaces;
  for (const Mesh* m : surfaces_of.meshes) surfaces.push_back(std::make_unique<const Surface>(*m));
  auto surface_at = [&](int ptr_index) -> const Surface* {
    const auto it = std::upper_bound(circuit_start.begin(), circuit_start.end(), ptr_index);
    return surfaces[it == circuit_start.begin() ? 0 : start_mesh[it - circuit_start.begin() - 1]]
        .get();
  };
  const Surface* surf = surface_at(0);
  ReplayResult r;
  r.eye_radius_by_hand = lathe2;
  r.blocks = static_cast<int>(program.blocks.size());
  r.min_clearance = std::numeric_limits<double>::infinity();
  Surface::Point P;
  P.p = planned.front();
  P.n = planned_n.front();
  P.fn = planned_n.front();
  // The last point that holds the fibre (pins, or a curved surface): beyond it on a flat face the
  // fibre is straight; lptr tracks what is laid for the deviation.
  Surface::Point anchor = P;
  auto anchor_flat = [&](const Surface::Point& q) {
    return std::fabs((q.p - anchor.p).dot(anchor.fn)) <= options.touch &&
           q.fn.dot(anchor.fn) >= 1.0 - 1e-9;
  };
  int ptr = 0, lptr = 0;
  int tied_at = 0;       // the planned point where the tow was last tied on
  int released_to = -1;  // the plan's points up to here are behind the contact
  double h_guess = 0.05;
  double dev_sum = 0.0;
  const int n_axes = lathe2 ? 2 : 4;
  const std::array<FeedAxis, 4> fa = feed_axes(machine);
  std::vector<AxisValues> values;
  std::vector<double> durations;
  std::vector<double> xs, as;
  const GcodeBlock* prev = nullptr;
  for (const GcodeBlock& b : program.blocks) {
    const AxisValues v{b.a, b.x, lathe2 ? (b.eye_radius > 0.0 ? b.eye_radius : eye_radius) : b.y,
                       b.b};
    double dur = 0.0;
    if (prev) {
      const AxisValues pv = values.back();
      double dist2 = 0.0, slow = 0.0;
      for (int a = 0; a < n_axes; ++a) {
        dist2 += (v[a] - pv[a]) * (v[a] - pv[a]);
        slow = std::max(slow, std::fabs(v[a] - pv[a]) / fa[a].max_velocity);
      }
      if (b.rapid) {
        dur = slow;
      } else if (b.inverse_time) {
        dur = dist2 > 0.0 ? 60.0 / b.feed : 0.0;
      } else {
        dur = std::sqrt(dist2) / (b.feed / 60.0);
      }
      // The eye's path in the mandrel frame, cut into sub-steps.
      const Vec3 e0 = eye_at(prev->a, prev->x, pv[2]);
      const Vec3 e1 = eye_at(b.a, b.x, v[2]);
      const double travel =
          std::hypot((e1 - e0).norm(), std::fabs(b.a - prev->a) * kPi / 180.0 *
                                           std::max(std::fabs(v[2]), std::fabs(pv[2])));
      if (b.rapid) {
        // A rapid move between layers: the tow is cut, and tied on again at the next layer's
        // first point after the last tie-on (export/program/gcode.h; a plan without layers: the
        // circuit after the contact's); no fibre is laid on the way. Not the circuit after the
        // contact's in a layup: where the pins at a layer's last turnaround release the fibre,
        // the contact steps onto the next layer's first point, and the circuit after it was the
        // next layer's SECOND one (the outer layer of a two-layer pipe laid 10.0 mm off the plan
        // with one eye cylinder, on lathe2, 73.68 mm, for both layers).
        int next = -1;
        if (const auto l = std::upper_bound(tie_on.begin(), tie_on.end(), tied_at);
            l != tie_on.end()) {
          next = *l;
        } else if (const auto c = std::upper_bound(circuit_start.begin(), circuit_start.end(), ptr);
                   c != circuit_start.end()) {
          next = *c;
        }
        if (next >= 0) {
          ptr = std::min<int>(next, static_cast<int>(planned.size()) - 1);
          tied_at = ptr;
          P.p = planned[ptr];
          P.n = planned_n[ptr];
          P.fn = planned_n[ptr];
          anchor = P;
          lptr = ptr;
          surf = surface_at(ptr);
        }
      }
      // Bounded before any sub-stepping (issue 28: a 1e9 mm jump was cut into 2e9 sub-steps):
      // one block's eye travel beyond 100 m, or beyond 1e6 sub-steps, is no winder's move.
      if (!b.rapid && !(travel <= kMaxBlockTravel && travel / options.step <= kMaxBlockSubsteps)) {
        throw InputError("program line " + std::to_string(b.line) + ": the eye travels " +
                         format_travel(travel) + " mm in one move (from line " +
                         std::to_string(prev->line) + "), beyond 100 m or 1e6 sub-steps of " +
                         "replay.step; no winder moves so far in one block");
      }
      const int n = b.rapid ? 0 : std::max(1, static_cast<int>(std::ceil(travel / options.step)));
      for (int k = 1; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        const Vec3 e = eye_at(prev->a + t * (b.a - prev->a), prev->x + t * (b.x - prev->x),
                              pv[2] + t * (v[2] - pv[2]));
        double dev = 0.0;
        // The pins catch the fibre as it arrives at the ring: within `catch_distance` before it.
        // An arc the fibre has left holds it no more (the deviation track may fall back on it).
        if (ptr <= released_to) ptr = std::min(released_to + 1, stretch_last[ptr]);
        const int last = stretch_last[ptr];    // this layer's (the tow's) last planned point
        const int first = stretch_first[ptr];  // and its first
        const int nh = next_held[ptr];
        // Measured along the plan from the foot of the contact on its planned segment (a straight
        // pass on a flat face is one long segment: from the segment's start the pins were never
        // within reach).
        double s_contact = planned_s[ptr];
        if (ptr < last) {
          const double seg = planned_s[ptr + 1] - planned_s[ptr];
          if (seg > 0.0) {
            s_contact += std::clamp((P.p - planned[ptr]).dot(planned[ptr + 1] - planned[ptr]) / seg,
                                    0.0, seg);
          }
        }
        if (!held[ptr] && nh >= 0 && planned_s[nh] - s_contact <= options.catch_distance) {
          ptr = nh;
        }
        const double probe = 4.0 * options.step;
        // The straight fibre anchor -> `to` (on the anchor's flat face) is held at both ends now:
        // it is laid; its points are compared with the plan.
        auto lay_segment = [&](const Vec3& to) {
          const double len = (to - anchor.p).norm();
          const int m = static_cast<int>(std::ceil(len / options.step));
          double worst = 0.0;
          for (int i = 1; i <= m; ++i) {
            const Vec3 q = anchor.p + (static_cast<double>(i) / m) * (to - anchor.p);
            worst = std::max(worst, track_polyline(planned, planned_s, q, options.search_back,
                                                   options.search_ahead, first, last, &lptr));
          }
          return worst;
        };
        if (held[ptr] && ptr < last) {
          // On a turnaround the pins or the boss lay the fibre along the plan: the contact moves
          // along the planned arc to the first point whose free fibre to the eye is tangent.
          // The tangency on the arc is judged with the plan's normal (the one the eye was put on:
          // the planner's dwell points carry the surface's interpolated normal, a flat face's
          // own); the point's facet (fn) tells a flat face, on the side of a rim the plan's is on.
          auto on_surface = [&](int i) {
            Surface::Point q = surf->project(planned[i], &planned_n[i]);
            q.p = planned[i];
            return q;
          };
          // A flat face, not a facet: the plane of pin i's facet reaches 2.5 probe (5 mm) both
          // ways along the arc (a coarse pipe's 36-gon has 8.7 mm facets, curved between them).
          auto flat_around = [&](int i, const Surface::Point& pi) {
            Vec3 t = planned[std::min(i + 1, last)] - planned[std::max(i - 1, 0)];
            t -= t.dot(pi.fn) * pi.fn;
            if (!(t.norm() > 1e-12)) return false;
            t *= 2.5 * probe / t.norm();
            for (const Vec3& q : {Vec3(planned[i] + t), Vec3(planned[i] - t)}) {
              const Surface::Point Q = surf->project(q, &pi.n);
              if (!Q.flat || (q - Q.p).norm() > options.touch || Q.fn.dot(pi.fn) < 1.0 - 1e-9) {
                return false;
              }
            }
            return true;
          };
          bool in_plane = false;
          auto wraps_on = [&](int i, const Surface::Point& pi) {
            const Vec3 d = e - planned[i];
            in_plane = options.touch > 0.0 && bend[i] != 0 &&
                       std::fabs(d.dot(pi.fn)) <= options.touch / probe * d.norm() &&
                       flat_around(i, pi);
            // An eye within `hold` below the pin's tangent plane is on it (the program's
            // rounding puts an eye swung in that plane a few 1e-4 mm below): the pin holds.
            if (!in_plane) return d.dot(planned_n[i]) < -options.hold;
            if (i + 1 <= last && held[i + 1]) {
              return bend[i] * pi.fn.dot(d.cross(planned[i + 1] - planned[i])) < 0.0;
            }
            return i > 0 && bend[i] * pi.fn.dot((planned[i] - planned[i - 1]).cross(d)) <= 0.0;
          };
          int j = ptr;
          Surface::Point pj = on_surface(j);
          bool released = false;
          while (j < last && held[j] && wraps_on(j, pj)) {
            if (!held[j + 1]) {
              // Off the arc's end. In a flat face's plane the fibre leaves the last pin and lies
              // straight on the face (the free walk from the pin); on a curved surface it leaves
              // the arc at its end, at the pass's first point (as it was laid before the flat
              // rule).
              if (in_plane) {
                released = true;
                break;
              }
            }
            pj = on_surface(++j);
          }
          // The fibre lay straight on a flat face beyond its anchor (it swung with the eye): the
          // pins hold its far end now, and it is laid.
          if ((P.p - anchor.p).norm() > 0.0 && anchor_flat(pj) && (pj.p - anchor.p).norm() > 0.0) {
            dev = lay_segment(pj.p);
          }
          P = pj;
          P.n = planned_n[j];
          anchor = P;
          if (released) released_to = j;
          ptr = released && held[j] ? std::min(j + 1, last) : j;
          lptr = ptr;
          ++r.held_substeps;
        } else {
          const Vec3* pin = nh >= 0 ? &planned[nh] : nullptr;
          // The fibre runs from its anchor (the last point that holds it: pins, or a curved
          // surface) straight over a flat face, then wraps on where the surface curves.
          Surface::Point flat_end = anchor;
          const double laid =
              lay_straight(*surf, e, &flat_end, probe, options.touch, pin, options.catch_distance);
          double seg_dev = 0.0;
          if (!(laid > 0.0)) {
            // No flat stretch: the contact walk (on a flat face beyond its anchor with the eye
            // lifted above the face, the fibre leaves at the anchor).
            P = anchor;
            advance(*surf, e, &P, &h_guess, 4.0 * options.step);
            anchor = P;
          } else {
            P = flat_end;
            Surface::Point wrap = flat_end;
            advance(*surf, e, &wrap, &h_guess, 4.0 * options.step);
            const Vec3 to_eye = e - anchor.p;
            if (to_eye.dot(anchor.fn) < -options.touch / probe * to_eye.norm() &&
                (!anchor_flat(wrap) || (wrap.p - flat_end.p).norm() > 1e-9)) {
              // The eye below the face's plane: the fibre is pressed onto the face and wraps on
              // where it curves (or walks on where the straight stretch stopped short of its
              // face's end: a facet with no planar vertex): held there, the stretch is laid.
              seg_dev = lay_segment(flat_end.p);
              anchor = wrap;
              P = wrap;
              lay_straight(*surf, e, &P, probe, options.touch, pin, options.catch_distance);
            }
          }
          r.straight_substeps += (P.p - anchor.p).norm() > 0.0;
          dev = track_polyline(planned, planned_s, P.p, options.search_back, options.search_ahead,
                               first, last, &ptr);
          if ((P.p - anchor.p).norm() > 0.0) {
            // The fibre lies on a flat face beyond its anchor, held at no far end: it swings with
            // the eye and is not laid yet; what is laid ends at the anchor.
            dev = track_polyline(planned, planned_s, anchor.p, options.search_back,
                                 options.search_ahead, first, last, &lptr);
          } else {
            lptr = ptr;
          }
          dev = std::max(dev, seg_dev);
        }
        if (const Surface* s = surface_at(ptr); s != surf) {
          // The plan moved on to a circuit wound on another surface without a rapid between:
          // the contact goes onto that surface.
          surf = s;
          P = surf->project(P.p, &P.n);
          anchor = P;
          lptr = ptr;
        }
        dev_sum += dev;
        ++r.substeps;
        if (dev > r.max_deviation) {
          r.max_deviation = dev;
          r.max_deviation_line = b.line;
          r.max_deviation_point = P.p;
        }
      }
      const double clear = surf->distance(e1);
      if (clear < r.min_clearance) {
        r.min_clearance = clear;
        r.min_clearance_line = b.line;
      }
    } else {
      // The first position: the fibre is tied on at the plan's first point (no walk: the mesh's
      // normals at a boundary are one-sided).
      const Vec3 e = eye_at(b.a, b.x, v[2]);
      r.min_clearance = surf->distance(e);
      r.min_clearance_line = b.line;
    }
    r.wind_time += dur;
    values.push_back(v);
    durations.push_back(dur);
    xs.push_back(b.x);
    as.push_back(b.a);
    auto grow = [&](double* lo, double* hi, double x) {
      if (!prev) {
        *lo = *hi = x;
      } else {
        *lo = std::min(*lo, x);
        *hi = std::max(*hi, x);
      }
    };
    grow(&r.a_min, &r.a_max, b.a);
    grow(&r.x_min, &r.x_max, b.x);
    grow(&r.y_min, &r.y_max, v[2]);
    grow(&r.b_min, &r.b_max, b.b);
    prev = &b;
  }
  r.mean_deviation = r.substeps > 0 ? dev_sum / r.substeps : 0.0;
  r.carriage_reversals = reversals(xs);
  r.spindle_reversals = reversals(as);
  r.limits = check_axis_limits(values, durations, n_axes, fa);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "replay: %d blocks, deviation max %.3f mm (line %d) mean %.4f mm, min clearance "
                "%.2f mm, wind time %.1f s, reversals X %d A %d",
                r.blocks, r.max_deviation, r.max_deviation_line, r.mean_deviation, r.min_clearance,
                r.wind_time, r.carriage_reversals, r.spindle_reversals);
  r.summary = buf;
  return r;
}

bool ReplayResult::within(double tolerance, ReplayExcess* excess) const {
  if (!(tolerance > 0.0) || !(max_deviation > tolerance)) return true;
  if (excess) {
    *excess = ReplayExcess();
    excess->deviation = max_deviation;
    excess->tolerance = tolerance;
    excess->line = max_deviation_line;
  }
  return false;
}

std::string ReplayResult::clearance_short(const std::string& program, double clearance,
                                          double slack, bool located) const {
  if (!(min_clearance < clearance - slack)) return "";
  char buf[240];
  std::snprintf(
      buf, sizeof buf,
      " %.3f mm from the surface of the layer in work%s, less than the clearance %.3f "
      "mm%s",
      min_clearance, located ? "" : (" at line " + std::to_string(min_clearance_line)).c_str(),
      clearance,
      eye_radius_by_hand ? " (a lathe2 layup: does each layer's stop name its eye radius?)" : "");
  if (located) {
    return program + ":" + std::to_string(min_clearance_line) + ": the replay puts the eye" + buf;
  }
  return "machine.envelope.clearance: the replay of " + program + " puts the eye" + buf +
         "; no program written";
}

std::string ReplayExcess::refused(const std::string& program) const {
  const std::string where = at.empty() ? "line " + std::to_string(line) : at;
  char buf[200];
  std::snprintf(buf, sizeof buf, " %.3f mm from the plan at %s, more than %.3f mm", deviation,
                where.c_str(), tolerance);
  return "machine.replay_tolerance: the replay of " + program +
         (eye ? " puts the eye" : " lays the fibre") + buf + "; no program written";
}

std::string ReplayExcess::located(const std::string& program) const {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                ": the replay %s %.3f mm from the plan, more than machine.replay_tolerance %.3f mm",
                eye ? "puts the eye" : "lays the fibre", deviation, tolerance);
  return (at.empty() ? program + ":" + std::to_string(line) : at) + buf;
}

}  // namespace windplan
