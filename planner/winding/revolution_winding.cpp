#include "planner/winding/revolution_winding.h"

#include <algorithm>
#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/mesh/closest_point.h"
#include "planner/winding/fibre_metrics.h"
#include "planner/winding/helix.h"

namespace windplan {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

}  // namespace

double fibre_step(const WindingOptions& o) { return std::clamp(0.125 * o.band_width, 0.25, 2.0); }

std::vector<Vec2> clip_meridian(const std::vector<Vec2>& m, double x0, double x1) {
  const double lo = std::isfinite(x0) ? x0 : -std::numeric_limits<double>::infinity();
  const double hi = std::isfinite(x1) ? x1 : std::numeric_limits<double>::infinity();
  std::vector<Vec2> out;
  auto cut = [](const Vec2& a, const Vec2& b, double x) {
    const double t = (x - a.x()) / (b.x() - a.x());
    return Vec2(x, a.y() + t * (b.y() - a.y()));
  };
  for (std::size_t i = 0; i < m.size(); ++i) {
    const bool in = m[i].x() >= lo && m[i].x() <= hi;
    if (i > 0) {
      const Vec2 &a = m[i - 1], &b = m[i];
      for (double x : {lo, hi}) {
        if (std::isfinite(x) && (a.x() - x) * (b.x() - x) < 0.0) out.push_back(cut(a, b, x));
      }
    }
    if (in) out.push_back(m[i]);
  }
  return out;
}

std::vector<Vec2> wound_meridian(const Mesh& annulus, const SpindleAxis& axis,
                                 const WindingOptions& o) {
  const std::vector<Vec2> whole = annulus_meridian(annulus, axis);
  const std::array<double, 2> range = {whole.front().x(), whole.back().x()};
  if (o.has_start_station()) check_station("winding.start_station", o.start_station, range);
  if (o.has_end_station()) check_station("winding.end_station", o.end_station, range);
  return clip_meridian(whole, o.start_station, o.end_station);
}

std::vector<Circuit> revolution_circuits(
    const Mesh& annulus, const std::vector<int>& face_map, const SpindleAxis& axis,
    const ClairautPass& pass, const PatternCandidate& pattern, const WindingOptions& options,
    double* projection_max, const std::array<std::vector<PassSample>, 2>* turnarounds) {
  const std::array<Vec3, 2> frame = axis_frame(axis);
  const std::vector<Vec3> vn = vertex_normals(annulus);
  const ClosestPointQuery query(annulus);
  const double window =
      options.curvature_window > 0.0 ? options.curvature_window : options.band_width;
  const double step = fibre_step(options);
  const std::vector<PassSample>& smp = pass.samples;
  const double Phi = pass.angle;
  double worst = 0.0;
  auto place = [&](double x, double r, double phi) {
    const Vec3 p = point_on_axis_frame(axis, frame, x, r, phi);
    const ClosestPointQuery::Hit hit = query.closest(p);
    worst = std::max(worst, hit.distance);
    FibrePoint q;
    q.position = hit.position;
    q.normal = point_normal(annulus, vn, hit.point);
    const int f = hit.point.element;
    q.face = face_map.empty() || f < 0 || f >= static_cast<int>(face_map.size()) ? f : face_map[f];
    return q;
  };
  // A dwell arc along the end circle (x, r) from phi on by delta.
  auto dwell = [&](double x, double r, double phi, double delta) {
    std::vector<FibrePoint> pts;
    const int n = std::max(2, static_cast<int>(std::ceil(r * delta / step)));
    for (int j = 0; j <= n; ++j) pts.push_back(place(x, r, phi + delta * j / n));
    return pts;
  };
  const int K = pattern.circuits;
  std::vector<Circuit> circuits(K);
  const bool friction_ends =
      turnarounds && (!(*turnarounds)[0].empty() || !(*turnarounds)[1].empty());
  if (friction_ends) {
    // Friction turnarounds: the fibre is one smooth curve from circuit to circuit, so each
    // circuit is annotated as a whole, padded with a window of its neighbours (the circuit
    // turned by -+ the advance), and the segment ends are no ends of the annotation.
    std::vector<std::array<double, 3>> cs;  // circuit 0: (x, r, phi)
    std::vector<int> ends;                  // the last sample of each segment
    auto add = [&](const std::vector<PassSample>& v, double phi, bool reverse) {
      for (std::size_t i = cs.empty() ? 0 : 1; i < v.size(); ++i) {
        const PassSample& q = reverse ? v[v.size() - 1 - i] : v[i];
        cs.push_back({q.x, q.r, reverse ? phi + (Phi - q.phi) : phi + q.phi});
      }
      ends.push_back(static_cast<int>(cs.size()) - 1);
    };
    // A friction turnaround is split at its apex (the axial extreme, where the carriage turns):
    // the fibre runs out to it and back, so the carriage reverses between segments, not in one.
    auto add_turnaround = [&](const std::vector<PassSample>& v, double phi, bool far_end) {
      const int begin = static_cast<int>(cs.size());
      add(v, phi, false);
      int apex = begin;
      for (int i = begin; i < static_cast<int>(cs.size()); ++i) {
        if (far_end ? cs[i][0] > cs[apex][0] : cs[i][0] < cs[apex][0]) apex = i;
      }
      if (apex > begin && apex < ends.back()) ends.insert(ends.end() - 1, apex);
    };
    const double d1 = (*turnarounds)[1].empty() ? 0.0 : (*turnarounds)[1].back().phi;
    add(smp, 0.0, false);
    if (!(*turnarounds)[1].empty()) add_turnaround((*turnarounds)[1], Phi, true);
    add(smp, Phi + d1, true);
    if (!(*turnarounds)[0].empty()) add_turnaround((*turnarounds)[0], 2.0 * Phi + d1, false);
    const double A = pattern.advance;
    // Start each circuit at the start end's apex, where the carriage turns (as a geodesic
    // circuit starts at its start dome's turnaround): the second half of the previous circuit's
    // start turnaround (turned back by A) leads, this circuit's first half ends it. The program
    // then starts and ends where the fibre turns around, not in the middle of a pass.
    if (!(*turnarounds)[0].empty() && ends.size() >= 2) {
      const int a = ends[ends.size() - 2];  // the start turnaround's apex (its split)
      const int n = static_cast<int>(cs.size());
      if (a > 0 && a < n - 1 && std::abs(cs[a][0] - cs.front()[0]) > 0.0) {
        std::vector<std::array<double, 3>> rot;
        for (int i = a; i < n; ++i) rot.push_back({cs[i][0], cs[i][1], cs[i][2] - A});
        for (int i = 1; i <= a; ++i) rot.push_back(cs[i]);
        const int shift = n - 1 - a;
        std::vector<int> moved = {shift};
        for (std::size_t i = 0; i + 1 < ends.size(); ++i) moved.push_back(ends[i] + shift);
        cs = std::move(rot);
        ends = std::move(moved);
      }
    }
    auto planned = [&](const std::array<double, 3>& q, double shift) {
      return point_on_axis_frame(axis, frame, q[0], q[1], q[2] + shift);
    };
    // How many samples of padding hold a window of fibre at each end.
    int pad_head = 0, pad_tail = 0;
    for (double run = 0.0; pad_head + 1 < static_cast<int>(cs.size()) && run < window;) {
      run += (planned(cs[pad_head + 1], 0) - planned(cs[pad_head], 0)).norm();
      ++pad_head;
    }
    for (double run = 0.0; pad_tail + 1 < static_cast<int>(cs.size()) && run < window;) {
      const std::size_t i = cs.size() - 1 - pad_tail;
      run += (planned(cs[i], 0) - planned(cs[i - 1], 0)).norm();
      ++pad_tail;
    }
    const int n = static_cast<int>(cs.size());
    for (int k = 0; k < K; ++k) {
      Circuit& c = circuits[k];
      c.index = k;
      const double phi0 = std::fmod(k * A, kTwoPi);
      std::vector<FibrePoint> pts;
      for (int i = n - 1 - pad_tail; i < n - 1; ++i) {
        pts.push_back(place(cs[i][0], cs[i][1], phi0 - A + cs[i][2]));
      }
      for (const auto& q : cs) pts.push_back(place(q[0], q[1], phi0 + q[2]));
      for (int i = 1; i <= pad_head; ++i) {
        pts.push_back(place(cs[i][0], cs[i][1], phi0 + A + cs[i][2]));
      }
      annotate_fibre_points(&pts, axis, window);
      const double s0 = pts[pad_tail].s;
      c.points.assign(pts.begin() + pad_tail, pts.begin() + pad_tail + n);
      for (FibrePoint& q : c.points) q.s -= s0;
      int first = 0;
      for (int e : ends) {
        c.segments.push_back({CircuitSegment::Kind::Pass, first, e});
        first = e;
      }
    }
    if (projection_max) *projection_max = worst;
    return circuits;
  }
  for (int k = 0; k < K; ++k) {
    Circuit& c = circuits[k];
    c.index = k;
    const double phi0 = std::fmod(k * pattern.advance, kTwoPi);
    std::vector<FibrePoint> out;
    for (const PassSample& s : smp) out.push_back(place(s.x, s.r, phi0 + s.phi));
    append_circuit_segment(&c, std::move(out), CircuitSegment::Kind::Pass, axis, window);
    const double d1 = pattern.dwell[1], d0 = pattern.dwell[0];
    if (d1 > 0.0) {
      append_circuit_segment(&c, dwell(smp.back().x, smp.back().r, phi0 + Phi, d1),
                             CircuitSegment::Kind::Turnaround, axis, window);
    }
    std::vector<FibrePoint> back;
    for (auto it = smp.rbegin(); it != smp.rend(); ++it) {
      back.push_back(place(it->x, it->r, phi0 + Phi + d1 + (Phi - it->phi)));
    }
    append_circuit_segment(&c, std::move(back), CircuitSegment::Kind::Pass, axis, window);
    if (d0 > 0.0) {
      append_circuit_segment(&c, dwell(smp.front().x, smp.front().r, phi0 + 2.0 * Phi + d1, d0),
                             CircuitSegment::Kind::Turnaround, axis, window);
    }
  }
  if (projection_max) *projection_max = worst;
  return circuits;
}

RevolutionWinding plan_revolution_winding(const Mesh& annulus, const std::vector<int>& face_map,
                                          const SpindleAxis& axis, const WindingOptions& o) {
  RevolutionWinding w;
  w.meridian = wound_meridian(annulus, axis, o);
  if (w.meridian.size() < 2) {
    throw ConfigError("winding.start_station / end_station: the stations leave no wound length");
  }
  w.problem = pattern_problem(w.meridian, o);
  if (!w.problem.reachable) return w;
  w.planned = true;
  if (wants_friction_turnarounds(w.problem, o)) {
    w.friction = true;
    w.friction_plan = plan_friction_winding(w.problem, o);
    w.problem.requested_c = w.friction_plan.requested_c;
    w.pattern = w.friction_plan.pattern;
    w.pass = w.friction_plan.pass;
  } else {
    w.pattern = choose_pattern(w.problem, o);
    w.pass = clairaut_pass(w.meridian, w.pattern.c, {fibre_step(o)});
  }
  w.geodesic_end = w.pass.turns_around;
  std::array<std::vector<PassSample>, 2> turns;
  for (int e : {0, 1}) {
    if (w.friction && w.friction_plan.friction_end[e]) {
      turns[e] = w.friction_plan.turnarounds[e].samples;
    }
  }
  w.circuits =
      revolution_circuits(annulus, face_map, axis, w.pass, w.pattern, o, &w.projection_max, &turns);
  return w;
}

}  // namespace windplan
