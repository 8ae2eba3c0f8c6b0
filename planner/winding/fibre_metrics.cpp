#include "planner/winding/fibre_metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/mesh/closest_point.h"

namespace windplan {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// Arc-length interpolation of a point attribute (position, normal) along a polyline (cumulative
// lengths `cum`), clamped to its ends.
Vec3 at_length(const std::vector<FibrePoint>& p, const std::vector<double>& cum, double s,
               Vec3 FibrePoint::*field = &FibrePoint::position) {
  const std::size_t n = p.size();
  if (s <= cum.front()) return p.front().*field;
  if (s >= cum.back()) return p.back().*field;
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), s) - cum.begin());
  const std::size_t a = std::min(i, n - 1) - 1, b = a + 1;
  const double d = cum[b] - cum[a];
  const double u = d > 0.0 ? (s - cum[a]) / d : 0.0;
  return (1.0 - u) * (p[a].*field) + u * (p[b].*field);
}

Vec3 chord_direction(const std::vector<FibrePoint>& p, const std::vector<double>& cum, double s,
                     double half) {
  const double lo = std::max(cum.front(), s - half), hi = std::min(cum.back(), s + half);
  const Vec3 d = at_length(p, cum, hi) - at_length(p, cum, lo);
  const double n = d.norm();
  return n > 0.0 ? Vec3(d / n) : Vec3::Zero();
}

double mean_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / v.size();
}
double cv_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  if (v.size() < 2 || !(m != 0.0)) return 0.0;
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / v.size()) / std::fabs(m);
}

// The curvature window w (mm) of the options: curvature_window, or the band width.
double curvature_window(const WindingOptions& o) {
  return o.curvature_window > 0.0 ? o.curvature_window : o.band_width;
}

// The points of a dwell arc (not yet annotated). The arc runs on the boundary (or across faces
// on a station circle): each point takes the normal of the face of the segment that leaves it.
std::vector<FibrePoint> turnaround_points(const Mesh& m, const LoopArc& arc) {
  std::vector<FibrePoint> pts;
  for (std::size_t i = 0; i < arc.points.size(); ++i) {
    FibrePoint q;
    q.position = arc.points[i];
    const int f = arc.faces[std::min(i, arc.faces.size() - 1)];
    q.normal = m.face_normal(f);
    q.face = f;
    pts.push_back(q);
  }
  return pts;
}

// The same points with the surface's interpolated vertex normals (for the circuit: the eye is put
// on the fibre's tangent, which the annotation projects onto the tangent plane of this normal; a
// face's own normal is half a facet angle off it, 3 deg on the 60 facets of an ellipse 160 x 100,
// which put the eye that far below the true tangent plane at the arc's end: the fibre wrapped on
// along the station beyond the last pin, 4.3 mm off the next pass). A flat face keeps its own
// normal: an edge of length l whose end normals differ by d (rad) would, were it a chord of a
// curved surface, stand l d / 8 off it; beyond kFlatSagitta no tessellation leaves a chord, so the
// face is flat (a rounded rectangle's side, 90 mm wide between corners whose first facets tilt its
// edges' normals 3 deg: 1.1 mm; the ellipse's facets: 0.04 mm), and the interpolated normals
// tilting across it are an artefact.
std::vector<FibrePoint> turnaround_points(const Mesh& m, const LoopArc& arc,
                                          const std::vector<Vec3>& vn) {
  constexpr double kFlatSagitta = 0.25;  // mm
  std::vector<FibrePoint> pts = turnaround_points(m, arc);
  for (FibrePoint& q : pts) {
    const Tri& t = m.triangle(q.face);
    const Vec3& a = m.points()[t[0]];
    const Vec3& b = m.points()[t[1]];
    const Vec3& c = m.points()[t[2]];
    double sagitta = 0.0;
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], v = t[(k + 1) % 3];
      const double cosang = std::clamp(vn[u].dot(vn[v]), -1.0, 1.0);
      sagitta = std::max(sagitta, (m.points()[v] - m.points()[u]).norm() * std::acos(cosang) / 8.0);
    }
    if (sagitta > kFlatSagitta) continue;
    Vec3 bary;
    closest_point_on_triangle(q.position, a, b, c, &bary);
    const Vec3 n = bary[0] * vn[t[0]] + bary[1] * vn[t[1]] + bary[2] * vn[t[2]];
    if (n.norm() > 1e-12) q.normal = n.normalized();
  }
  return pts;
}

// Stability figures of runs of annotated fibre points (passes or dwell arcs). A segment counts
// as above mu when the mean slippage of its two ends exceeds mu, as bridging when the mean k_n
// of its ends is below -kBridgeTol.
struct RunStability {
  static constexpr double kBridgeTol = 1e-5;  // 1/mm
  double length = 0.0, max_slippage = 0.0, slip_length = 0.0, bridging_length = 0.0;

  void add(const std::vector<FibrePoint>& p, int first, int last, double mu) {
    for (int j = first; j <= last; ++j) {
      max_slippage = std::max(max_slippage, p[j].slippage);
      if (j == first) continue;
      const FibrePoint& a = p[j - 1];
      const FibrePoint& b = p[j];
      const double L = b.s - a.s;
      length += L;
      if (0.5 * (a.slippage + b.slippage) > mu) slip_length += L;
      if (0.5 * (a.k_n + b.k_n) < -kBridgeTol) bridging_length += L;
    }
  }
  double slip_fraction() const { return length > 0.0 ? slip_length / length : 0.0; }
};

void add_run(const RunStability& r, TurnaroundStability* t) {
  t->length += r.length;
  t->max_slippage = std::max(t->max_slippage, r.max_slippage);
  t->slip_length += r.slip_length;
  t->bridging_length += r.bridging_length;
  t->slip_fraction = t->length > 0.0 ? t->slip_length / t->length : 0.0;
}

std::string fmt(double x, int prec = 3) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(prec);
  o << x;
  return o.str();
}

// "the start station circle (winding.start_station = 50.000 mm)" / "the end loop (polar opening
// or tube end)": where the dwell arcs of one end run, for warnings.
std::string turnaround_place(int end, const TurnaroundStability& t) {
  const std::string which = end == 0 ? "start" : "end";
  if (t.at_station()) {
    return "the " + which + " station circle (winding." + which + "_station = " + fmt(t.station) +
           " mm)";
  }
  return "the " + which + " loop (polar opening or tube end)";
}

// The slippage and bridging warnings of the passes and, per end, of the dwell arcs.
void add_stability_warnings(PlanMetrics* metrics, double pass_slip_length,
                            const WindingOptions& options) {
  PlanMetrics& pm = *metrics;
  if (pm.max_slippage > options.mu) {
    pm.warnings.push_back("slippage: max |k_g/k_n| = " + fmt(pm.max_slippage) +
                          " exceeds mu = " + fmt(options.mu) + " on " + fmt(pass_slip_length, 1) +
                          " mm (" + fmt(100.0 * pm.slip_fraction, 2) +
                          "% of the pass length): the fibre may slip there" +
                          // beta shapes the passes only when it is above 0
                          (options.beta > 0.0 ? " (lower beta)" : ""));
  }
  if (pm.bridging_length > 0.0) {
    pm.warnings.push_back("bridging: " + fmt(pm.bridging_length, 1) +
                          " mm of pass with k_n <= 0: the fibre would bridge a concave region");
  }
  for (int e = 0; e < 2; ++e) {
    const TurnaroundStability& t = pm.turnaround_ends[e];
    if (t.max_slippage > options.mu) {
      pm.warnings.push_back(
          "turnaround slippage: max |k_g/k_n| = " + fmt(t.max_slippage) + " on the dwell arcs " +
          "along " + turnaround_place(e, t) + " exceeds mu = " + fmt(options.mu) + " by " +
          fmt(t.max_slippage - options.mu) + ", on " + fmt(t.slip_length, 1) + " mm (" +
          fmt(100.0 * t.slip_fraction, 2) + "% of the turnaround length there): the fibre may " +
          "slip off the turnaround (a circle about the axis is a geodesic only where the radius " +
          "does not change along the axis" +
          (t.at_station() ? ": move the station onto a cylindrical part)"
                          : ": a boss or pin ring must hold the fibre there, or turn around on a "
                            "station on a cylindrical part)"));
    }
    if (t.bridging_length > 0.0) {
      pm.warnings.push_back("turnaround bridging: " + fmt(t.bridging_length, 1) +
                            " mm of dwell arc along " + turnaround_place(e, t) +
                            " with k_n <= 0: the fibre would bridge a concave region");
    }
  }
}

// A pass's length, end angles and radii and largest slippage, read off its circuit segment.
void fill_pass_figures(const Circuit& c, const CircuitSegment& seg, const SpindleAxis& axis,
                       PassReport* r) {
  const FibrePoint& a = c.points[seg.first];
  const FibrePoint& b = c.points[seg.last];
  r->length = b.s - a.s;
  r->angle_start = a.winding_angle;
  r->angle_end = b.winding_angle;
  r->radius_start = axis.radius(a.position);
  r->radius_end = axis.radius(b.position);
  for (int j = seg.first; j <= seg.last; ++j) {
    r->max_slippage = std::max(r->max_slippage, c.points[j].slippage);
  }
}

}  // namespace

Vec3 point_normal(const Mesh& m, const std::vector<Vec3>& vn, const SurfacePoint& p) {
  Vec3 n = Vec3::Zero();
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      n = vn[p.element];
      break;
    case SurfacePoint::Kind::Edge:
      n = (1.0 - p.t) * vn[m.from(p.element)] + p.t * vn[m.to(p.element)];
      break;
    case SurfacePoint::Kind::Face: {
      const Tri& t = m.triangle(p.element);
      n = p.bary[0] * vn[t[0]] + p.bary[1] * vn[t[1]] + p.bary[2] * vn[t[2]];
      break;
    }
  }
  return n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::UnitX();
}

std::vector<Vec3> vertex_normals(const Mesh& m) {
  std::vector<Vec3> n(m.num_vertices(), Vec3::Zero());
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 fn = m.face_normal(f);
    for (int k = 0; k < 3; ++k) n[m.triangle(f)[k]] += m.corner_angle(3 * f + k) * fn;
  }
  for (Vec3& x : n) {
    if (x.norm() > 0.0) x.normalize();
  }
  return n;
}

double winding_angle_deg(const SpindleAxis& axis, const Vec3& n, const Vec3& t) {
  const Vec3 mer = axis.direction - axis.direction.dot(n) * n;
  if (!(mer.norm() > 1e-12) || !(t.norm() > 0.0)) return 90.0;
  const double c = std::clamp(std::fabs(t.normalized().dot(mer.normalized())), 0.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

void annotate_fibre_points(std::vector<FibrePoint>* points, const SpindleAxis& axis, double window,
                           double s0) {
  std::vector<FibrePoint>& p = *points;
  const std::size_t n = p.size();
  if (n == 0) return;
  std::vector<double> cum(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    cum[i] = cum[i - 1] + (p[i].position - p[i - 1].position).norm();
  // A window no longer than the polyline itself.
  const double w = std::max(1e-9, std::min(window, cum.back()));
  const double half = 0.5 * w;
  auto tangent_at = [&](double s, const Vec3& nrm) {
    Vec3 t = chord_direction(p, cum, s, half);
    t -= t.dot(nrm) * nrm;
    return t.norm() > 0.0 ? Vec3(t.normalized()) : t;
  };
  for (std::size_t i = 0; i < n; ++i) {
    FibrePoint& q = p[i];
    q.s = s0 + cum[i];
    const Vec3 t = tangent_at(cum[i], q.normal);
    if (t.norm() > 0.0) q.tangent = t;
    q.winding_angle = winding_angle_deg(axis, q.normal, q.tangent);
    // The window keeps its full width at the ends of the polyline (shifted inwards, one-sided):
    // a window cut to half there held too little bend, and k_g / k_n of two tiny values spiked.
    const double lo = std::clamp(cum[i] - half, 0.0, cum.back() - w), hi = lo + w;
    // Chord tangents (unprojected) at both ends of the window, over the distance between the
    // chords' midpoints (chords are cut at the polyline's ends).
    auto chord_mid = [&](double x) {
      return 0.5 * (std::max(0.0, x - half) + std::min(cum.back(), x + half));
    };
    const double span = chord_mid(hi) - chord_mid(lo);
    if (!(span > 0.0)) {
      q.k_n = q.k_g = q.slippage = 0.0;
      continue;
    }
    const Vec3 ta = chord_direction(p, cum, lo, half), tb = chord_direction(p, cum, hi, half);
    const Vec3 dt = (tb - ta) / span;
    // Split into normal and geodesic parts in the frame where the window is centred (the
    // point's own frame except in a shifted end window).
    Vec3 nc = q.normal, tc = q.tangent;
    const double centre = 0.5 * (chord_mid(lo) + chord_mid(hi));
    if (std::fabs(centre - cum[i]) > 1e-9 * w) {
      nc = at_length(p, cum, centre, &FibrePoint::normal);
      if (nc.norm() > 0.0) nc.normalize();
      const Vec3 t = tangent_at(centre, nc);
      if (t.norm() > 0.0) tc = t;
    }
    q.k_n = -dt.dot(nc);  // > 0 where the fibre bends towards the mandrel (convex)
    q.k_g = dt.dot(nc.cross(tc));
    // A fibre bent by less than kStraightFibreCurvature (a radius of 10 m) is straight to the
    // measurement: k_g / k_n of two such values is noise (the ends of traced helix passes on a
    // coarse bent pipe measured 0.25-410 from curvatures of 1e-8..1e-5 / mm), and it does not slip.
    q.slippage = std::hypot(q.k_n, q.k_g) < kStraightFibreCurvature ? 0.0
                 : std::fabs(q.k_n) > 1e-12                    ? std::fabs(q.k_g / q.k_n)
                                            : (std::fabs(q.k_g) > 1e-12 ? kUnboundedSlippage : 0.0);
  }
}

std::vector<FibrePoint> path_points(const Mesh& m, const SurfacePath& path,
                                    const std::vector<Vec3>& vn) {
  std::vector<FibrePoint> out;
  const std::vector<int> faces = segment_faces(m, path);
  auto add = [&](const SurfacePoint& sp, int face) {
    FibrePoint q;
    q.position = position(m, sp);
    q.normal = point_normal(m, vn, sp);
    q.face = face;
    out.push_back(q);
  };
  if (!path.closed) add(path.start, faces.empty() ? path.start_face : faces.front());
  for (int i = 0; i < path.num_crossings(); ++i) {
    add(SurfacePoint::on_edge(path.halfedges[i], path.lambdas[i]),
        i < static_cast<int>(faces.size()) ? faces[i] : -1);
  }
  if (!path.closed) add(path.end, faces.empty() ? path.start_face : faces.back());
  return out;
}

void append_circuit_segment(Circuit* c, std::vector<FibrePoint> pts, CircuitSegment::Kind kind,
                            const SpindleAxis& axis, double window) {
  const double s = c->points.empty() ? 0.0 : c->points.back().s;
  annotate_fibre_points(&pts, axis, window, s);
  if (pts.empty()) return;
  // The first point repeats the previous segment's last point: keep one copy.
  const int first = c->points.empty() ? 0 : static_cast<int>(c->points.size()) - 1;
  const std::size_t skip = c->points.empty() ? 0 : 1;
  // A pass owns its first point's annotation (its direction, not the turnaround's).
  if (!c->points.empty() && kind == CircuitSegment::Kind::Pass) c->points.back() = pts.front();
  for (std::size_t i = skip; i < pts.size(); ++i) c->points.push_back(pts[i]);
  c->segments.push_back({kind, first, static_cast<int>(c->points.size()) - 1});
}

std::vector<Circuit> build_circuits(const Mesh& m, const HelixPlan& plan,
                                    const std::vector<int>& face_map, const SpindleAxis& axis,
                                    const WindingOptions& options) {
  const std::vector<Vec3> vn = vertex_normals(m);
  const double window = curvature_window(options);
  const int K = plan.summary.circuits;
  std::vector<Circuit> circuits;
  for (int k = 0; k < K; ++k) {
    Circuit c;
    c.index = k;
    auto append = [&](std::vector<FibrePoint> pts, CircuitSegment::Kind kind) {
      append_circuit_segment(&c, std::move(pts), kind, axis, window);
    };
    append(path_points(m, plan.passes[2 * k].path, vn), CircuitSegment::Kind::Pass);
    append(turnaround_points(m, plan.turnarounds[2 * k].arc, vn), CircuitSegment::Kind::Turnaround);
    append(path_points(m, plan.passes[2 * k + 1].path, vn), CircuitSegment::Kind::Pass);
    append(turnaround_points(m, plan.turnarounds[2 * k + 1].arc, vn),
           CircuitSegment::Kind::Turnaround);
    if (!face_map.empty()) {
      for (FibrePoint& q : c.points) {
        if (q.face >= 0 && q.face < static_cast<int>(face_map.size())) q.face = face_map[q.face];
      }
    }
    circuits.push_back(std::move(c));
  }
  return circuits;
}

SpacingStats turn_spacing(const Mesh& m, const HelixPlan& plan,
                          const std::vector<double>& face_girth, const SpindleAxis& axis,
                          int meridians) {
  struct Hit {
    double h;
    Vec3 p;
    int face;
  };
  std::vector<std::vector<Hit>> hits(meridians);
  for (const HelixPass& pass : plan.passes) {
    if (pass.hand != 1) continue;
    const SurfacePath& path = pass.path;
    const std::vector<int> faces = segment_faces(m, path);
    // (theta, h, position) at every polyline point, theta unwrapped along the path.
    std::vector<std::array<double, 2>> th;
    std::vector<Vec3> pos;
    // Ends: edge points on the loops, or face points on the station circles.
    auto add_point = [&](const SurfacePoint& sp) {
      th.push_back(surface_point_coordinates(m, plan.coords, sp));
      pos.push_back(position(m, sp));
    };
    add_point(path.start);
    for (int i = 0; i < path.num_crossings(); ++i) {
      add_point(SurfacePoint::on_edge(path.halfedges[i], path.lambdas[i]));
    }
    add_point(path.end);
    for (std::size_t i = 1; i < th.size(); ++i) {
      th[i][0] -= kTwoPi * std::round((th[i][0] - th[i - 1][0]) / kTwoPi);
    }
    for (std::size_t i = 0; i + 1 < th.size(); ++i) {
      const double a = th[i][0], b = th[i + 1][0];
      if (a == b) continue;
      const double lo = std::min(a, b), hi = std::max(a, b);
      for (int j = 0; j < meridians; ++j) {
        const double tm = kTwoPi * j / meridians;
        for (double q = std::ceil((lo - tm) / kTwoPi); tm + kTwoPi * q < hi; q += 1.0) {
          const double u = (tm + kTwoPi * q - a) / (b - a);
          hits[j].push_back({(1 - u) * th[i][1] + u * th[i + 1][1],
                             (1 - u) * pos[i] + u * pos[i + 1],
                             faces[std::min(i, faces.size() - 1)]});
        }
      }
    }
  }
  std::vector<double> mm, norm;
  for (auto& list : hits) {
    std::sort(list.begin(), list.end(), [](const Hit& a, const Hit& b) { return a.h < b.h; });
    for (std::size_t i = 0; i + 1 < list.size(); ++i) {
      const double d = (list[i + 1].p - list[i].p).norm();
      if (!std::isfinite(d)) continue;  // zero spacing (turns piled up) counts
      double g = 0.0;
      if (!face_girth.empty()) {
        g = 0.5 * (face_girth[list[i].face] + face_girth[list[i + 1].face]);
      } else {
        g = kTwoPi * axis.radius(0.5 * (list[i].p + list[i + 1].p));
      }
      mm.push_back(d);
      if (g > 0.0) norm.push_back(d / g);
    }
  }
  SpacingStats s;
  s.samples = static_cast<int>(mm.size());
  s.mean = mean_of(mm);
  s.cv = cv_of(mm);
  s.mean_normalised = mean_of(norm);
  s.cv_normalised = cv_of(norm);
  return s;
}

std::vector<PassReport> pass_reports(const HelixPlan& plan, const std::vector<Circuit>& circuits,
                                     const SpindleAxis& axis) {
  std::vector<PassReport> out;
  for (std::size_t i = 0; i < plan.passes.size(); ++i) {
    const HelixPass& p = plan.passes[i];
    PassReport r;
    r.circuit = p.circuit;
    r.hand = p.hand;
    r.iterations = p.summary.iterations;
    r.time_ms = p.summary.time_ms;
    r.termination = to_string(p.summary.termination);
    const Circuit& c = circuits[p.circuit];
    int seg_index = p.hand == 1 ? 0 : 2;
    if (seg_index < static_cast<int>(c.segments.size())) {
      fill_pass_figures(c, c.segments[seg_index], axis, &r);
    }
    out.push_back(r);
  }
  return out;
}

PlanMetrics compute_plan_metrics(const Mesh& m, const HelixPlan& plan,
                                 const std::vector<Circuit>& circuits,
                                 const std::vector<double>& face_girth, const SpindleAxis& axis,
                                 bool revolution, const WindingOptions& options) {
  PlanMetrics pm;
  const int K = plan.summary.circuits;
  pm.circuits = K;
  pm.turns_per_pass = options.turns;
  pm.band_width = options.band_width;
  pm.friction = options.mu;
  for (const Circuit& c : circuits) {
    if (!c.points.empty()) pm.fibre_length += c.points.back().s;
  }
  // Spacing.
  const SpacingStats sp = turn_spacing(m, plan, face_girth, axis, options.meridians);
  pm.spacing_mean = sp.mean;
  pm.spacing_cv = sp.cv_normalised;

  // Coverage at the largest radius of the passes (mean over the out passes).
  double R = 0.0, cos_sum = 0.0;
  int cos_n = 0;
  double girth_at_R = 0.0;
  for (const Circuit& c : circuits) {
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind != CircuitSegment::Kind::Pass) continue;
      int best = seg.first;
      for (int j = seg.first; j <= seg.last; ++j) {
        if (axis.radius(c.points[j].position) > axis.radius(c.points[best].position)) best = j;
      }
      const double r = axis.radius(c.points[best].position);
      if (r > R) {
        R = r;
        girth_at_R = kTwoPi * r;
      }
      cos_sum += std::cos(c.points[best].winding_angle * M_PI / 180.0);
      ++cos_n;
    }
  }
  const double ca = cos_n > 0 ? cos_sum / cos_n : 1.0;
  const double band_length = girth_at_R * ca;  // circumference seen across the band direction
  if (band_length > 0.0) {
    pm.circuits_for_coverage =
        std::max(1, static_cast<int>(std::ceil(band_length / options.band_width - 1e-9)));
    pm.cover_factor = K * options.band_width / band_length;
  }
  const int p = plan.summary.pattern_step;
  if (revolution) {
    pm.pattern = "K=" + std::to_string(K) + ", advance " + std::to_string(p) + "/" +
                 std::to_string(K) + " turn per circuit, " +
                 (std::gcd(p, K) == 1 ? "coprime: closes after " + std::to_string(K) + " circuits"
                                      : "not coprime");
  } else {
    pm.pattern = "K=" + std::to_string(K) + ", advance " + std::to_string(p) + "/" +
                 std::to_string(K) + " of the conformal angle (not a shape of revolution)";
  }

  // Stability on the passes.
  RunStability passes;
  for (const Circuit& c : circuits) {
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind != CircuitSegment::Kind::Pass) continue;
      passes.add(c.points, seg.first, seg.last, options.mu);
    }
  }
  pm.max_slippage = passes.max_slippage;
  pm.slip_fraction = passes.slip_fraction();
  pm.bridging_length = passes.bridging_length;

  // Stability on the turnarounds: each dwell arc annotated on its own points and window, as
  // build_circuits annotates it before joining it to its passes (whose annotation the circuit
  // keeps at the two junction points), so the figures do not depend on the corner where a pass
  // meets the arc (see the header comment).
  const double window = curvature_window(options);
  for (const Turnaround& t : plan.turnarounds) {
    std::vector<FibrePoint> pts = turnaround_points(m, t.arc);
    annotate_fibre_points(&pts, axis, window);
    RunStability arc;
    if (!pts.empty()) arc.add(pts, 0, static_cast<int>(pts.size()) - 1, options.mu);
    TurnaroundStability& end = pm.turnaround_ends[t.loop == 0 ? 0 : 1];
    end.station = t.station;
    add_run(arc, &end);
    add_run(arc, &pm.turnarounds);
  }

  for (const std::string& w : plan.summary.warnings) pm.warnings.push_back(w);
  add_stability_warnings(&pm, passes.slip_length, options);
  return pm;
}

}  // namespace windplan

namespace windplan {

std::vector<PassReport> circuit_pass_reports(const std::vector<Circuit>& circuits,
                                             const SpindleAxis& axis, const std::string& how) {
  std::vector<PassReport> out;
  for (const Circuit& c : circuits) {
    int hand = 1;
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind != CircuitSegment::Kind::Pass) continue;
      PassReport r;
      r.circuit = c.index;
      r.hand = hand;
      hand = -hand;
      r.termination = how;
      fill_pass_figures(c, seg, axis, &r);
      out.push_back(r);
    }
  }
  return out;
}

PlanMetrics circuit_plan_metrics(const std::vector<Circuit>& circuits, const SpindleAxis& axis,
                                 const WindingOptions& options) {
  PlanMetrics pm;
  pm.circuits = static_cast<int>(circuits.size());
  pm.band_width = options.band_width;
  pm.friction = options.mu;
  RunStability passes;
  const double window = curvature_window(options);
  for (const Circuit& c : circuits) {
    if (!c.points.empty()) pm.fibre_length += c.points.back().s;
    int dwell = 0;  // the first dwell arc of a circuit is at the far end, the second at the start
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind == CircuitSegment::Kind::Pass) {
        passes.add(c.points, seg.first, seg.last, options.mu);
        continue;
      }
      // A dwell arc on its own points and window, as compute_plan_metrics does.
      std::vector<FibrePoint> pts(c.points.begin() + seg.first, c.points.begin() + seg.last + 1);
      annotate_fibre_points(&pts, axis, window);
      RunStability arc;
      arc.add(pts, 0, static_cast<int>(pts.size()) - 1, options.mu);
      const int end = dwell++ == 0 ? 1 : 0;
      TurnaroundStability& t = pm.turnaround_ends[end];
      t.station = end == 0 ? options.start_station : options.end_station;
      add_run(arc, &t);
      add_run(arc, &pm.turnarounds);
    }
  }
  pm.max_slippage = passes.max_slippage;
  pm.slip_fraction = passes.slip_fraction();
  pm.bridging_length = passes.bridging_length;
  add_stability_warnings(&pm, passes.slip_length, options);
  return pm;
}

}  // namespace windplan
