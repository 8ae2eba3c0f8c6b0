// Tracing in the conformal coordinates of the annulus (planner/winding/helix_trace.h): helices,
// loop arcs, station circles and arcs, and the coordinates of surface points.
#include "planner/winding/helix_trace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/region/plane_section.h"

namespace windplan {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Corner index of vertex v in face f.
int corner_of(const Mesh& m, int f, int v) {
  const Tri& t = m.triangle(f);
  return t[0] == v ? 0 : (t[1] == v ? 1 : 2);
}

// Lifted theta of from(h) and to(h) in face(h) (interior h).
std::array<double, 2> lift_on(const Mesh& m, const HarmonicCoordinates& hc, int h) {
  const int f = m.face(h), k = h % 3;
  return {hc.corner_theta(m, f, k), hc.corner_theta(m, f, (k + 1) % 3)};
}

// The interior halfedge of an edge point's boundary edge (the point's own halfedge or its twin).
int interior_boundary_halfedge(const Mesh& m, const SurfacePoint& p, double* t) {
  if (p.kind != SurfacePoint::Kind::Edge || p.element < 0 || p.element >= m.num_halfedges()) {
    throw InputError("helix start: " + to_string(m, p) + " is not an edge point");
  }
  int h = p.element;
  *t = p.t;
  if (m.is_boundary_halfedge(h)) {
    h = m.twin(h);
    *t = 1.0 - p.t;
  }
  if (!m.is_boundary_halfedge(m.twin(h))) {
    throw InputError("helix start: " + to_string(m, p) + " is not on a boundary edge");
  }
  return h;
}

// Boundary loop as interior halfedges ordered so that theta increases along the loop: step i
// runs from vertex v[i] to v[i+1]; forward[i] says whether from(h[i]) == v[i].
struct OrientedLoop {
  std::vector<int> h;
  std::vector<char> forward;
};

OrientedLoop oriented_loop_of(const Mesh& m, const HarmonicCoordinates& hc, int interior_h) {
  // Find the boundary loop holding twin(interior_h), in next() order.
  const int b0 = m.twin(interior_h);
  std::vector<int> bl;
  int b = b0;
  do {
    bl.push_back(b);
    b = m.next(b);
  } while (b != b0 && static_cast<int>(bl.size()) <= m.num_halfedges());
  // Along boundary halfedge b (from(b) -> to(b)) the interior twin runs backwards.
  double total = 0.0;
  for (int bb : bl) {
    const auto l = lift_on(m, hc, m.twin(bb));
    total += l[0] - l[1];
  }
  OrientedLoop o;
  if (total >= 0.0) {
    for (int bb : bl) {
      o.h.push_back(m.twin(bb));
      o.forward.push_back(0);  // step from(b) = to(twin) -> to(b) = from(twin)
    }
  } else {
    for (auto it = bl.rbegin(); it != bl.rend(); ++it) {
      o.h.push_back(m.twin(*it));
      o.forward.push_back(1);
    }
  }
  return o;
}

Vec3 edge_position(const Mesh& m, int h, double t) {
  return (1.0 - t) * m.position(m.from(h)) + t * m.position(m.to(h));
}

// The point with barycentric coordinates b in face f.
Vec3 face_position(const Mesh& m, int f, const Vec3& b) {
  const Tri& t = m.triangle(f);
  return b[0] * m.position(t[0]) + b[1] * m.position(t[1]) + b[2] * m.position(t[2]);
}

// Lifted theta (in face f's lift) and height at barycentric coordinates b in face f.
std::array<double, 2> face_coordinates(const Mesh& m, const HarmonicCoordinates& hc, int f,
                                       const Vec3& b) {
  double th = 0.0, hh = 0.0;
  for (int k = 0; k < 3; ++k) {
    th += b[k] * hc.corner_theta(m, f, k);
    hh += b[k] * hc.height[m.triangle(f)[k]];
  }
  return {th, hh};
}

std::string num_str(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}
}  // namespace

std::array<double, 2> edge_point_coordinates(const Mesh& m, const HarmonicCoordinates& hc, int h,
                                             double t) {
  if (m.is_boundary_halfedge(h)) {
    h = m.twin(h);
    t = 1.0 - t;
  }
  const auto l = lift_on(m, hc, h);
  const double th = (1.0 - t) * l[0] + t * l[1];
  const double hh = (1.0 - t) * hc.height[m.from(h)] + t * hc.height[m.to(h)];
  return {th, hh};
}

SurfacePoint loop_point_at_theta(const Mesh& m, const HarmonicCoordinates& hc,
                                 const std::vector<int>& loop, double theta) {
  if (loop.empty()) throw InputError("loop_point_at_theta: empty loop");
  // Any interior halfedge on the loop's boundary.
  int start = -1;
  for (int h : m.outgoing_halfedges(loop[0])) {
    if (m.is_boundary_halfedge(m.twin(h))) start = h;
    if (m.is_boundary_halfedge(m.twin(m.prev(h)))) start = m.prev(h);
    if (start >= 0) break;
  }
  if (start < 0)
    throw InputError("loop_point_at_theta: vertex " + std::to_string(loop[0]) +
                     " is not on the boundary");
  const OrientedLoop o = oriented_loop_of(m, hc, start);
  for (std::size_t i = 0; i < o.h.size(); ++i) {
    const auto l = lift_on(m, hc, o.h[i]);
    const double a = l[0], b = l[1];
    const double lo = std::min(a, b), hi = std::max(a, b);
    const double q = std::ceil((lo - theta) / kTwoPi);
    const double target = theta + kTwoPi * q;
    if (target <= hi && hi > lo) {
      const double t = std::clamp((target - a) / (b - a), 0.0, 1.0);
      return SurfacePoint::on_edge(o.h[i], t);
    }
  }
  throw TopologyError("no point of the boundary loop has angle " + std::to_string(theta));
}

std::array<double, 2> surface_point_coordinates(const Mesh& m, const HarmonicCoordinates& hc,
                                                const SurfacePoint& p) {
  if (p.kind == SurfacePoint::Kind::Edge) return edge_point_coordinates(m, hc, p.element, p.t);
  const int f = containing_face(m, p);
  if (f < 0) throw InputError("harmonic coordinates: " + to_string(m, p) + " is in no face");
  return face_coordinates(m, hc, f, barycentric_in_face(m, f, p));
}

SurfacePath trace_helix(const Mesh& m, const HarmonicCoordinates& hc, const SurfacePoint& start,
                        double turns, int hand, const HelixTraceOptions& options) {
  if (!(turns > 0.0) || !std::isfinite(turns)) {
    throw InputError("trace_helix: turns must be > 0 (got " + num_str(turns) + ")");
  }
  if (hand != 1 && hand != -1) throw InputError("trace_helix: hand must be +1 or -1");
  if (!(options.height_span > 0.0) || !std::isfinite(options.height_span)) {
    throw InputError("trace_helix: height_span must be > 0 (got " + num_str(options.height_span) +
                     ")");
  }
  const double k2piN = hand * kTwoPi * turns / options.height_span;
  // Level function in face f at corner k: lifted theta - hand 2 pi N h / span.
  auto phi = [&](int f, int k) {
    return hc.corner_theta(m, f, k) - k2piN * hc.height[m.triangle(f)[k]];
  };
  const bool stops = std::isfinite(options.stop_station);

  SurfacePath path;
  path.closed = false;
  int f = -1;
  int entry = -1;  // the halfedge of f the path came in through; -1: it starts inside f
  int dir = hand;  // +1: towards loop 1 (h increasing), -1: towards loop 0
  double level = 0.0;
  Vec3 here = Vec3::Zero();  // the current point, barycentric in f (for the station stop)
  const bool on_boundary =
      start.kind == SurfacePoint::Kind::Edge && start.element >= 0 &&
      start.element < m.num_halfedges() &&
      (m.is_boundary_halfedge(start.element) || m.is_boundary_halfedge(m.twin(start.element)));
  if (on_boundary || start.kind == SurfacePoint::Kind::Vertex) {
    double t0 = 0.0;
    const int h0 = interior_boundary_halfedge(m, start, &t0);
    dir = hc.height[m.from(h0)] < 0.5 ? 1 : -1;  // away from the start loop
    f = m.face(h0);
    level = (1.0 - t0) * phi(f, h0 % 3) + t0 * phi(f, (h0 % 3 + 1) % 3);
    path.start = SurfacePoint::on_edge(h0, t0);
    entry = h0;
  } else {
    const int limit = start.kind == SurfacePoint::Kind::Edge ? m.num_halfedges() : m.num_faces();
    if (start.element < 0 || start.element >= limit) {
      throw InputError("helix start: element " + std::to_string(start.element) +
                       " is not a point of the mesh");
    }
    // Inside the annulus: the level set through the point, run towards loop 1 (hand +1) or
    // loop 0 (hand -1).
    f = containing_face(m, start);
    path.start = start;
    level = 0.0;
    const Vec3 b = barycentric_in_face(m, f, start);
    for (int k = 0; k < 3; ++k) level += b[k] * phi(f, k);
  }
  path.start_face = f;
  here = barycentric_in_face(m, f, path.start);
  // A face can be crossed once per (started) turn (long CAD triangles span the whole length).
  const double steps_cap = 4.0 * (std::ceil(turns) + 1.0) * m.num_faces() + 64.0;
  const int max_steps = steps_cap < std::numeric_limits<int>::max()
                            ? static_cast<int>(steps_cap)
                            : std::numeric_limits<int>::max();
  for (int step = 0; step < max_steps; ++step) {
    int best = -1;
    double best_lambda = 0.0;
    bool best_strict = false;
    double best_height = 0.0;
    if (entry >= 0) {
      for (int h : {m.next(entry), m.prev(entry)}) {
        const double a = phi(f, h % 3) - level, b = phi(f, (h % 3 + 1) % 3) - level;
        if (a == b) continue;
        const bool strict = (a < 0.0 && b > 0.0) || (a > 0.0 && b < 0.0);
        const bool touch = a == 0.0 || b == 0.0;
        if (!strict && !touch) continue;
        if (best >= 0 && (best_strict || !strict)) continue;
        best = h;
        best_lambda = std::clamp(-a / (b - a), 0.0, 1.0);
        best_strict = strict;
      }
    } else {
      // Starting inside f: of the level segment's two ends, the one further along dir.
      for (int k = 0; k < 3; ++k) {
        const int h = 3 * f + k;
        const double a = phi(f, k) - level, b = phi(f, (k + 1) % 3) - level;
        if (a == b) continue;
        if (!((a <= 0.0 && b >= 0.0) || (a >= 0.0 && b <= 0.0))) continue;
        const double l = std::clamp(-a / (b - a), 0.0, 1.0);
        const double hh = (1.0 - l) * hc.height[m.from(h)] + l * hc.height[m.to(h)];
        if (best >= 0 && dir * hh <= dir * best_height) continue;
        best = h;
        best_lambda = l;
        best_height = hh;
      }
    }
    if (best < 0) {
      throw TopologyError("helix tracing: the level set stops in face " + std::to_string(f) +
                          " (degenerate conformal coordinates there)");
    }
    if (stops) {
      // The axial coordinate is linear along the segment here -> exit: stop where it reaches
      // the station.
      Vec3 there = Vec3::Zero();
      there[best % 3] = 1.0 - best_lambda;
      there[(best % 3 + 1) % 3] = best_lambda;
      const double s = options.stop_station;
      const double a0 = options.axis.axial(face_position(m, f, here));
      const double a1 = options.axis.axial(face_position(m, f, there));
      if (dir * (a1 - s) >= 0.0) {
        const double u = a1 != a0 ? std::clamp((s - a0) / (a1 - a0), 0.0, 1.0) : 1.0;
        path.end = SurfacePoint::in_face(f, (1.0 - u) * here + u * there);
        return path;
      }
    }
    const int tw = m.twin(best);
    if (m.is_boundary_halfedge(tw)) {
      const double hb = 0.5 * (hc.height[m.from(best)] + hc.height[m.to(best)]);
      const int end_loop = hb < 0.5 ? 0 : 1;
      if (end_loop != (dir > 0 ? 1 : 0)) {
        throw TopologyError("helix tracing: the level set returns to its start loop at face " +
                            std::to_string(f) + " (the harmonic height is not monotone there)");
      }
      if (stops) {
        throw TopologyError("helix tracing: the level set reaches boundary loop " +
                            std::to_string(end_loop) + " at face " + std::to_string(f) +
                            " before the station at " + num_str(options.stop_station) + " mm");
      }
      path.end = SurfacePoint::on_edge(best, best_lambda);
      return path;
    }
    path.halfedges.push_back(best);
    // Off the vertices: a level set through a vertex would start the core on it.
    const double l = std::clamp(best_lambda, 1e-6, 1.0 - 1e-6);
    path.lambdas.push_back(l);
    // Move into the next face; re-express the level in its lift (differs by k 2 pi).
    const int g = m.face(tw);
    const int v = m.from(best);
    level += hc.face_offset[g][corner_of(m, g, v)] - hc.face_offset[f][corner_of(m, f, v)];
    f = g;
    entry = tw;
    // The crossing (1 - l) from(best) + l to(best) seen from g: to(best) = from(tw).
    here = Vec3::Zero();
    here[tw % 3] = l;
    here[(tw % 3 + 1) % 3] = 1.0 - l;
  }
  throw TopologyError("helix tracing: the level set does not reach the other loop (stopped after " +
                      std::to_string(max_steps) + " faces)");
}

LoopArc loop_arc(const Mesh& m, const HarmonicCoordinates& hc, const SurfacePoint& start,
                 double dwell) {
  double t = 0.0;
  const int h = interior_boundary_halfedge(m, start, &t);
  const OrientedLoop o = oriented_loop_of(m, hc, h);
  const int n = static_cast<int>(o.h.size());
  int i = static_cast<int>(std::find(o.h.begin(), o.h.end(), h) - o.h.begin());
  LoopArc arc;
  Vec3 p = edge_position(m, h, t);
  arc.points.push_back(p);
  // u: parameter along step i in loop direction.
  double u = o.forward[i] ? t : 1.0 - t;
  double remaining = std::max(0.0, dwell);
  for (int guard = 0; guard <= 2 * n + 2; ++guard) {
    const int hi = o.h[i];
    const auto l = lift_on(m, hc, hi);
    const double a = o.forward[i] ? l[0] : l[1], b = o.forward[i] ? l[1] : l[0];  // along loop
    const double th_now = a + u * (b - a);
    const double left = b - th_now;
    if (left >= remaining && b > a) {
      const double u_end = u + remaining / (b - a);
      const double t_end = o.forward[i] ? u_end : 1.0 - u_end;
      const double te = std::clamp(t_end, 1e-6, 1.0 - 1e-6);  // off the loop's vertices
      arc.end = SurfacePoint::on_edge(hi, te);
      const Vec3 q = edge_position(m, hi, te);
      arc.length += (q - arc.points.back()).norm();
      arc.points.push_back(q);
      arc.faces.push_back(m.face(hi));
      return arc;
    }
    remaining -= std::max(0.0, left);
    const Vec3 q = m.position(o.forward[i] ? m.to(hi) : m.from(hi));
    arc.length += (q - arc.points.back()).norm();
    arc.points.push_back(q);
    arc.faces.push_back(m.face(hi));
    i = (i + 1) % n;
    u = 0.0;
  }
  throw TopologyError("turnaround: theta does not increase along the boundary loop");
}

StationCircle station_circle(const Mesh& m, const HarmonicCoordinates& hc, const SpindleAxis& axis,
                             double station, const std::string& key) {
  const std::vector<PlaneSection> secs =
      plane_sections(m, axis.direction, axis.direction.dot(axis.origin) + station, axis);
  int best = -1;
  for (int i = 0; i < static_cast<int>(secs.size()); ++i) {
    if (secs[i].around && (best < 0 || secs[i].length > secs[best].length)) best = i;
  }
  if (best < 0) {
    throw ConfigError(key + " = " + num_str(station) +
                      " mm: the plane normal to the spindle axis there cuts the wound region in " +
                      std::to_string(secs.size()) +
                      " piece(s), none a loop around the mandrel (a station needs one)");
  }
  const SurfacePath& sp = secs[best].path;
  const int n = sp.num_crossings();
  if (n < 3) {
    throw TopologyError(key + ": the station circle at " + num_str(station) + " mm has only " +
                        std::to_string(n) + " edge crossings");
  }
  // Segment i (crossing i -> i + 1) lies in the face the section enters through crossing i.
  std::vector<SurfacePoint> c(n);
  std::vector<int> faces(n);
  std::vector<double> inc(n);
  for (int i = 0; i < n; ++i) c[i] = SurfacePoint::on_edge(sp.halfedges[i], sp.lambdas[i]);
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    const int g = m.face(m.twin(sp.halfedges[i]));
    faces[i] = g;
    const double a = face_coordinates(m, hc, g, barycentric_in_face(m, g, c[i]))[0];
    const double b = face_coordinates(m, hc, g, barycentric_in_face(m, g, c[(i + 1) % n]))[0];
    inc[i] = b - a;
    total += inc[i];
  }
  if (total < 0.0) {
    // Reverse: new segment j joins old crossings n-1-j and n-2-j, i.e. old segment n-2-j.
    std::reverse(c.begin(), c.end());
    std::vector<int> rf(n);
    std::vector<double> ri(n);
    for (int j = 0; j < n; ++j) {
      const int old = ((n - 2 - j) % n + n) % n;
      rf[j] = faces[old];
      ri[j] = -inc[old];
    }
    faces = std::move(rf);
    inc = std::move(ri);
    total = -total;
  }
  if (std::fabs(total - kTwoPi) > 0.5) {
    throw TopologyError(key + ": the conformal angle changes by " + num_str(total) +
                        " rad around the station circle at " + num_str(station) +
                        " mm (expected 2 pi)");
  }
  StationCircle circle;
  circle.station = station;
  circle.crossings = c;
  circle.faces = faces;
  circle.theta.resize(n + 1);
  circle.theta[0] = face_coordinates(m, hc, faces[0], barycentric_in_face(m, faces[0], c[0]))[0];
  for (int i = 0; i < n; ++i) circle.theta[i + 1] = circle.theta[i] + inc[i];
  double weighted = 0.0;
  for (int i = 0; i < n; ++i) circle.points.push_back(position(m, c[i]));
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const double len = (circle.points[j] - circle.points[i]).norm();
    const double ha = edge_point_coordinates(m, hc, c[i].element, c[i].t)[1];
    const double hb = edge_point_coordinates(m, hc, c[j].element, c[j].t)[1];
    circle.length += len;
    weighted += 0.5 * len * (ha + hb);
  }
  circle.height = circle.length > 0.0 ? weighted / circle.length
                                      : edge_point_coordinates(m, hc, c[0].element, c[0].t)[1];
  return circle;
}

LoopArc station_arc(const Mesh& m, const StationCircle& circle, const SurfacePoint& start,
                    double dwell) {
  const int n = static_cast<int>(circle.crossings.size());
  if (n < 3 || static_cast<int>(circle.theta.size()) != n + 1 ||
      static_cast<int>(circle.faces.size()) != n) {
    throw InputError("turnaround: the station circle at " + num_str(circle.station) +
                     " mm is empty or inconsistent");
  }
  // Where start is: the nearest segment (it lies on the circle up to rounding).
  const Vec3 p = position(m, start);
  int i = 0;
  double u = 0.0, dist = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    const Vec3& a = circle.points[j];
    const Vec3 ab = circle.points[(j + 1) % n] - a;
    const double l2 = ab.squaredNorm();
    const double uj = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    const double d = (a + uj * ab - p).norm();
    if (d < dist) dist = d, i = j, u = uj;
  }
  if (dist > 1e-6 * std::max(circle.length, 1.0)) {
    throw TopologyError("turnaround: " + to_string(m, start) + " is " + num_str(dist) +
                        " mm from the station circle at " + num_str(circle.station) + " mm");
  }
  // The point at parameter v of segment j, barycentric in its face.
  auto on_segment = [&](int j, double v) {
    const int g = circle.faces[j];
    const Vec3 b = (1.0 - v) * barycentric_in_face(m, g, circle.crossings[j]) +
                   v * barycentric_in_face(m, g, circle.crossings[(j + 1) % n]);
    return SurfacePoint::in_face(g, b);
  };
  LoopArc arc;
  arc.points.push_back(p);
  const double lap = circle.theta[n] - circle.theta[0];
  double offset = 0.0;  // whole laps passed
  const double target =
      circle.theta[i] + u * (circle.theta[i + 1] - circle.theta[i]) + std::max(0.0, dwell);
  const int guard = (static_cast<int>(std::max(0.0, dwell) / std::max(lap, 1e-9)) + 2) * n + 2;
  for (int step = 0; step < guard; ++step) {
    const double a = circle.theta[i] + offset, b = circle.theta[i + 1] + offset;
    if (b >= target && b > a) {
      // Strictly inside the segment: off the crossings, so inside the face.
      const double v = std::clamp((target - a) / (b - a), 1e-6, 1.0 - 1e-6);
      arc.end = on_segment(i, v);
      const Vec3 q = position(m, arc.end);
      arc.length += (q - arc.points.back()).norm();
      arc.points.push_back(q);
      arc.faces.push_back(circle.faces[i]);
      return arc;
    }
    const Vec3& q = circle.points[(i + 1) % n];
    arc.length += (q - arc.points.back()).norm();
    arc.points.push_back(q);
    arc.faces.push_back(circle.faces[i]);
    if (++i == n) {
      i = 0;
      offset += lap;
    }
  }
  throw TopologyError("turnaround: theta does not increase along the station circle at " +
                      num_str(circle.station) + " mm");
}

std::array<double, 2> station_range(const Mesh& m, const std::array<std::vector<int>, 2>& loops,
                                    const SpindleAxis& axis) {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  for (int v : loops[0]) lo = std::max(lo, axis.axial(m.position(v)));
  for (int v : loops[1]) hi = std::min(hi, axis.axial(m.position(v)));
  return {lo, hi};
}

void check_station(const std::string& key, double station, const std::array<double, 2>& range) {
  if (station > range[0] && station < range[1]) return;
  std::ostringstream s;
  s << key << " = " << station << " mm is outside the wound region: a station must lie"
    << " strictly between the boundary loops, in (" << range[0] << ", " << range[1]
    << ") mm along the spindle axis";
  if (!(range[0] < range[1])) s << " (the loops overlap along the axis: no station fits)";
  throw ConfigError(s.str());
}

}  // namespace windplan
