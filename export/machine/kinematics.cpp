#include "export/machine/kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>

#include "export/machine/clearance.h"
#include "export/machine/clearance_eye.h"
#include "export/machine/monotone_axes.h"
#include "export/machine/monotone_by_payout.h"
#include "export/machine/resample.h"
#include "export/machine/tangent_smoothing.h"
#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "geometry/mesh/closest_point.h"

namespace windplan {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Brings `raw` (deg) within 180 of `prev` by whole turns: the unwrapped continuation.
double unwrap_deg(double raw, double prev) { return prev + std::remainder(raw - prev, 360.0); }

}  // namespace

double AxisFrame::angle(const Vec3& p) const {
  const Vec3 q = p - origin;
  const double a = q.dot(u);
  const double b = q.dot(v);
  if (a == 0.0 && b == 0.0) return 0.0;
  return std::atan2(b, a);
}

AxisFrame make_axis_frame(const SpindleAxis& axis) {
  AxisFrame f;
  f.origin = axis.origin;
  const double n = axis.direction.norm();
  if (!(n > 0.0) || !std::isfinite(n)) throw InputError("the spindle axis has no direction");
  f.d = axis.direction / n;
  // The world axis least aligned with d; ties go to the first one (x, y, z).
  int best = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::fabs(f.d[i]) < std::fabs(f.d[best]) - 1e-12) best = i;
  }
  const Vec3 e = Vec3::Unit(best);
  f.u = (e - e.dot(f.d) * f.d).normalized();
  f.v = f.d.cross(f.u);
  return f;
}

EyeSolution solve_payout_eye(const AxisFrame& frame, const Envelope& env, const Vec3& p,
                             const Vec3& t_in, const std::string& where) {
  const std::string at = where.empty() ? std::string() : where + ": ";
  const double tn = t_in.norm();
  if (!(tn > 1e-12) || !std::isfinite(tn)) {
    throw InputError(at + "the fibre tangent is zero or not finite");
  }
  const Vec3 t = t_in / tn;
  if (!p.allFinite()) throw InputError(at + "the fibre point is not finite");
  EyeSolution s;
  if (env.fixed_length) {
    s.free_length = env.free_length;
    s.eye = p + env.free_length * t;
    return s;
  }
  auto f = [&](double l) {
    const Vec3 e = p + l * t;
    return frame.radius(e) - env.radius_at(frame.axial(e));
  };
  const double r0 = frame.radius(p);
  const double renv0 = env.radius_at(frame.axial(p));
  double fl = r0 - renv0;
  if (!(fl < 0.0)) {
    throw InputError(at + "the clearance envelope (radius " + num(renv0) + " mm at axial " +
                     num(frame.axial(p)) + " mm) is inside the mandrel (point radius " + num(r0) +
                     " mm)");
  }
  const double t_perp = (t - t.dot(frame.d) * frame.d).norm();
  if (t_perp < 1e-12) {
    throw InputError(at +
                     "the fibre tangent is parallel to the spindle axis and never leaves "
                     "the clearance envelope");
  }
  const double r_max = *std::max_element(env.r.begin(), env.r.end());
  // Beyond l_max the radius t_perp * l - r0 exceeds every envelope radius.
  const double l_max = (r_max + r0) / t_perp + 1.0;
  const double lipschitz = 1.0 + env.max_slope;
  double lo = 0.0, l = 0.0;
  int it = 0;
  while (fl < 0.0) {
    // Sphere tracing: |f'| <= lipschitz, so no root lies within -f / lipschitz.
    const double step = std::max(-fl / lipschitz, 1e-7);
    lo = l;
    l += step;
    fl = f(l);
    if (++it > 1000000 || l > l_max) {
      throw InputError(at + "the fibre tangent never leaves the clearance envelope");
    }
  }
  double hi = l;
  while (hi - lo > 1e-10) {
    const double mid = 0.5 * (lo + hi);
    if (f(mid) < 0.0) {
      lo = mid;
    } else {
      hi = mid;
    }
    ++it;
  }
  s.free_length = 0.5 * (lo + hi);
  s.eye = p + s.free_length * t;
  s.iterations = it;
  return s;
}

bool uses_inverse_time(const GcodeOptions& g) {
  if (g.feed == "inverse_time") return true;
  if (g.feed == "per_minute") return false;
  return g.dialect == "linuxcnc";
}

std::array<FeedAxis, 4> feed_axes(const MachineOptions& opts) {
  return {FeedAxis{opts.a.max_velocity, opts.a.max_acceleration},
          FeedAxis{opts.x.max_velocity, opts.x.max_acceleration},
          FeedAxis{opts.y.max_velocity, opts.y.max_acceleration},
          FeedAxis{opts.b.max_velocity, opts.b.max_acceleration}};
}

int driven_axes(const MachineOptions& opts) { return opts.kind == "lathe2" ? 2 : 4; }

namespace {

// Sign changes between consecutive non-zero moves of v[begin..end); calls at(i) with the index of
// the turning value for each.
template <class F>
int count_reversals(const std::vector<double>& v, int begin, int end, F at) {
  int count = 0, dir = 0, last = begin;
  for (int i = begin + 1; i < end; ++i) {
    const double d = v[i] - v[i - 1];
    if (std::fabs(d) < 1e-9) continue;
    const int s = d > 0 ? 1 : -1;
    if (dir != 0 && s != dir) {
      ++count;
      at(last);
    }
    dir = s;
    last = i;
  }
  return count;
}

// Reversal figures of one circuit's states [begin, end).
void count_circuit_reversals(const Circuit& c, const std::vector<MachineState>& st, int begin,
                             int end, Motion* m) {
  std::vector<double> xs(st.size()), as(st.size());
  for (int i = begin; i < end; ++i) {
    xs[i] = st[i].x_mm;
    as[i] = st[i].a_deg;
  }
  // The pass containing dense index k strictly inside it, or nullptr.
  auto pass_of = [&c](int k) -> const CircuitSegment* {
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind == CircuitSegment::Kind::Pass && k > seg.first && k < seg.last) return &seg;
    }
    return nullptr;
  };
  const int cx = count_reversals(xs, begin, end, [&](int i) {
    const int k = st[i].index;
    if (const CircuitSegment* seg = pass_of(k)) {
      const double s0 = c.points[seg->first].s, s1 = c.points[seg->last].s;
      const double s = c.points[k].s;
      if (s > s0 + 0.25 * (s1 - s0) && s < s1 - 0.25 * (s1 - s0)) ++m->mid_pass_carriage_reversals;
    }
  });
  m->carriage_reversals += cx;
  m->max_carriage_reversals_per_circuit = std::max(m->max_carriage_reversals_per_circuit, cx);
  m->spindle_reversals += count_reversals(as, begin, end, [&](int i) {
    if (pass_of(st[i].index)) ++m->spindle_reversals_in_passes;
  });
}

// The eye of a clearance-eye solution, as the envelope's solver gives it.
EyeSolution eye_solution(const ClearanceEye& ce) {
  EyeSolution es;
  es.eye = ce.eye;
  es.free_length = ce.free_length;
  es.iterations = ce.iterations;
  return es;
}

}  // namespace

Motion compute_motion(const WindingPlan& plan, const MachineOptions& opts, const Mesh* mandrel,
                      const std::vector<const Mesh*>& circuit_surfaces) {
  std::string why;
  if (!opts.is_valid(&why)) throw ConfigError("machine: " + why);
  Motion m;
  m.inverse_time = uses_inverse_time(opts.gcode);
  m.layers = plan.layers;
  const AxisFrame frame = make_axis_frame(plan.axis);
  // A robot's eye follows the mandrel itself (export/machine/clearance_eye.h) when there is a
  // mesh to measure the clearance on; otherwise, and on lathes, the envelope of the swept mandrel.
  const bool true_distance = opts.kind == "robot" && opts.envelope.mode() == "clearance" &&
                             mandrel && mandrel->num_faces() > 0;
  const Envelope env = true_distance
                           ? Envelope{}
                           : make_envelope(swept_profile(plan, mandrel), opts.envelope, opts.kind);
  m.envelope = true_distance ? "true distance " + num(opts.envelope.clearance) +
                                   " mm from the mandrel (robot: the eye follows the tube)"
                             : env.description;
  const bool lathe2 = opts.kind == "lathe2";
  // Machine axes that move (and bound the time): lathe2 drives A and X only.
  const AxisOptions* axes[4] = {&opts.a, &opts.x, &opts.y, &opts.b};
  const char* names[4] = {"A", "X", "Y", "B"};
  const char* units[4] = {"deg", "mm", "mm", "deg"};
  const int n_axes = driven_axes(opts);
  std::unique_ptr<ClosestPointQuery> query;
  if (mandrel && mandrel->num_faces() > 0) query = std::make_unique<ClosestPointQuery>(*mandrel);
  // A robot's eye on a layup keeps its clearance from the surface of the layer in work (each
  // circuit's entry of circuit_surfaces; null or missing: the mandrel): one query per distinct
  // surface, built once. Lathes: see layer_envelopes below.
  std::vector<const Mesh*> surface_meshes;
  std::vector<std::unique_ptr<ClosestPointQuery>> surface_queries;
  std::vector<int> surface_of(plan.circuits.size(), -1);  // -1: the mandrel and `query`
  // lathes (and a robot without a mesh) on a layup: the eye envelope of each circuit is the
  // clearance envelope of the surface it is wound on, swept (not the bare mandrel's: the lathe
  // replay of a two-layer pipe measured the eye 16.32 mm from the outer layer's surface with 20
  // reported on the mandrel), and its clearance is checked on that surface. lathe2 (no
  // cross-feed): each layer's eye cylinder is that surface's largest radius + the clearance (the
  // operator sets it at the stop before the layer: export/program/gcode.h); an explicit
  // envelope.radius or profile stays one envelope, its clearance checked on each layer's surface.
  const bool layer_envelopes = !true_distance && !env.fixed_length && mandrel &&
                               mandrel->num_faces() > 0 && opts.envelope.mode() == "clearance";
  const bool layer_clearance = mandrel && mandrel->num_faces() > 0;
  std::vector<Envelope> surface_envelopes;  // per entry of surface_meshes
  if (true_distance || layer_clearance) {
    for (std::size_t ci = 0; ci < plan.circuits.size() && ci < circuit_surfaces.size(); ++ci) {
      const Mesh* sm = circuit_surfaces[ci];
      if (!sm || sm == mandrel) continue;
      if (sm->num_faces() == 0)
        throw InputError("the surface under circuit " + std::to_string(ci) + " is empty");
      auto it = std::find(surface_meshes.begin(), surface_meshes.end(), sm);
      if (it == surface_meshes.end()) {
        surface_meshes.push_back(sm);
        surface_queries.push_back(std::make_unique<ClosestPointQuery>(*sm));
        surface_envelopes.push_back(
            layer_envelopes ? make_envelope(swept_profile(plan, sm), opts.envelope, opts.kind)
                            : env);
        it = surface_meshes.end() - 1;
      }
      surface_of[ci] = static_cast<int>(it - surface_meshes.begin());
    }
    m.clearance_on_layers = !surface_meshes.empty();
    if (!surface_meshes.empty() && layer_envelopes && lathe2 && !(opts.envelope.radius > 0.0)) {
      m.envelope = "cylinder per layer, largest radius of the layer in work + " +
                   num(opts.envelope.clearance) + " mm: r = " + num(env.r.front());
      for (const Envelope& e : surface_envelopes) m.envelope += ", " + num(e.r.front());
      m.envelope += " mm (set by hand at each layer's stop; the clearance from the layer in work)";
    } else if (!surface_meshes.empty() && layer_envelopes && !lathe2) {
      m.envelope = env.description + ", of the surface of the layer in work";
    } else if (!surface_meshes.empty() && !true_distance) {
      m.envelope = env.description + ", its clearance measured from the layer in work";
    } else if (!surface_meshes.empty()) {
      m.envelope =
          "true distance " + num(opts.envelope.clearance) +
          " mm from the surface of the layer in work (robot: the eye follows the laminate)";
    }
  }
  m.required_clearance = env.fixed_length ? 0.0 : opts.envelope.clearance;
  // A robot's eyes are planned at the clearance plus two chord tolerances, so that the eye keeps
  // the clearance between targets too: one for the targets' chords (within chord_tolerance of
  // the dense eyes, in the cell's axes as well), one for the turn of the eye about the E1 axis
  // between two targets (export/robot/robot_motion.h: a turn of the eye's angle about the E1 axis
  // by d at radius Y cuts the chord Y (1 - cos(d / 2)) inside the arc; the targets inserted where
  // that turns keep it within chord_tolerance). Eyes at exactly the clearance were replayed 19.94
  // to 19.95 mm from the surface between the targets on the shipped cells; here >= 20.04 mm.
  // (Eyes further out than the clearance used to make the replay lose the fibre at a layup's
  // second layer, 16 mm off: a bug of the replay's deviation track, which took the next layer's
  // first point for the contact's nearest and then tied the tow on a circuit too far;
  // export/program/replay.cpp.)
  const double eye_clearance =
      true_distance ? opts.envelope.clearance + kRobotEyeChords * opts.chord_tolerance
                    : opts.envelope.clearance;
  double min_clearance = std::numeric_limits<double>::infinity();

  // Per circuit, independent of the others: the smoothed tangents, the eye of every dense point,
  // its clearance and the chord resampling. Run in parallel; every circuit writes its own slot,
  // and an error is kept with its circuit and rethrown below where the serial loop would meet it
  // (before any later circuit's results are used), so the message does not depend on threads.
  struct CircuitMotion {
    std::vector<Vec3> tangent;
    std::vector<EyeSolution> sol;
    ClearanceCheck clearance;
    ResampleResult resampled;
    double max_tangent_change = 0.0;  // deg
    int max_eye_iterations = 0;
    int fibre_into_mandrel = 0;
    std::exception_ptr error;
    // A robot's corner eyes (insert_corner_eyes): per entry of tangent and sol, its dense point,
    // fibre position and arc length; empty when none is inserted.
    std::vector<int> dense;
    std::vector<Vec3> position;
    std::vector<double> s;
  };
  // Where a robot's fibre tangent turns by more than kCornerDeg between two dense points (a pass
  // meeting a dwell arc on the pins at a tube's end: 14.5 deg on bent_tube) the eye swings round
  // the contact by L times the angle, and the straight move between the two eyes cuts inside the
  // clearance (0.54 mm on bent_tube, measured by the replay). Eyes are inserted there with the
  // tangent turned in steps of at most kCornerDeg (slerp; the fibre point on the chord between
  // the two), each at the true clearance. Returns the number of eyes; fills the arrays of `cm`
  // and first_of (dense index -> entry).
  constexpr double kCornerDeg = 2.0;
  // The eye of fibre point p at the true clearance with the tangent turned the fraction f of the
  // angle ang from ta to tb (slerp), counting a tangent that enters the mandrel.
  struct TurnedEye {
    Vec3 t = Vec3::Zero();  // unit tangent
    EyeSolution es;
  };
  auto turned_eye = [](const Mesh& mesh, const ClosestPointQuery& q, const Vec3& p, const Vec3& ta,
                       const Vec3& tb, double ang, double f, double clearance, CircuitMotion* cm) {
    const Vec3 t = (std::sin((1.0 - f) * ang) * ta + std::sin(f * ang) * tb) / std::sin(ang);
    const ClearanceEye ce = solve_clearance_eye(mesh, q, p, t, clearance);
    if (ce.enters) ++cm->fibre_into_mandrel;
    return TurnedEye{t.normalized(), eye_solution(ce)};
  };
  auto insert_corner_eyes = [&](const Mesh& mesh, const ClosestPointQuery& q, double clearance,
                                const std::vector<double>& s_dense, std::vector<Vec3>* fibre,
                                std::vector<Vec3>* eyes, CircuitMotion* cm,
                                std::vector<int>* first_of) {
    const int n = static_cast<int>(fibre->size());
    std::vector<Vec3> fibre2, eyes2, tangent2;
    std::vector<EyeSolution> sol2;
    std::vector<int> dense;
    std::vector<double> s2;
    first_of->assign(n, 0);
    bool inserted = false;
    for (int i = 0; i < n; ++i) {
      if (i > 0) {
        const Vec3& ta = cm->tangent[i - 1];
        const Vec3& tb = cm->tangent[i];
        const double ang = std::acos(std::clamp(ta.dot(tb), -1.0, 1.0));
        const int parts = static_cast<int>(std::ceil(ang * kDeg / kCornerDeg));
        for (int k = 1; k < parts && std::sin(ang) > 1e-9; ++k) {
          const double f = static_cast<double>(k) / parts;
          const Vec3 p = (1.0 - f) * (*fibre)[i - 1] + f * (*fibre)[i];
          const TurnedEye te = turned_eye(mesh, q, p, ta, tb, ang, f, clearance, cm);
          fibre2.push_back(p);
          eyes2.push_back(te.es.eye);
          tangent2.push_back(te.t);
          sol2.push_back(te.es);
          dense.push_back(i - 1);
          s2.push_back((1.0 - f) * s_dense[i - 1] + f * s_dense[i]);
          inserted = true;
        }
      }
      (*first_of)[i] = static_cast<int>(fibre2.size());
      fibre2.push_back((*fibre)[i]);
      eyes2.push_back((*eyes)[i]);
      tangent2.push_back(cm->tangent[i]);
      sol2.push_back(cm->sol[i]);
      dense.push_back(i);
      s2.push_back(s_dense[i]);
    }
    if (!inserted) {
      first_of->clear();
      return n;
    }
    *fibre = std::move(fibre2);
    *eyes = std::move(eyes2);
    cm->tangent = std::move(tangent2);
    cm->sol = std::move(sol2);
    cm->position = *fibre;
    cm->dense = std::move(dense);
    cm->s = std::move(s2);
    return static_cast<int>(fibre->size());
  };
  std::vector<CircuitMotion> per_circuit(plan.circuits.size());
  // The smoothed tangents first, for every circuit: a robot's circuit that goes on from the
  // previous one's last point turns the eye from that circuit's last tangent (link eyes, below).
  parallel_for_index(static_cast<int>(plan.circuits.size()), [&](int ordinal) {
    const Circuit& c = plan.circuits[ordinal];
    const int n = static_cast<int>(c.points.size());
    if (n == 0) return;
    std::vector<Vec3> fibre(n), raw_t(n);
    std::vector<double> s(n), kappa(n);
    for (int i = 0; i < n; ++i) {
      const FibrePoint& fp = c.points[i];
      fibre[i] = fp.position;
      raw_t[i] = fp.tangent;
      s[i] = fp.s;
      kappa[i] = std::hypot(fp.k_n, fp.k_g);
    }
    // Pieces: a dwell arc (Turnaround) is its own piece, consecutive passes form one (they meet
    // tangentially); the smoothing window does not cross a corner between pieces.
    std::vector<int> piece(n, 0);
    {
      int id = 0;
      bool prev_turn = false;
      for (std::size_t g = 0; g < c.segments.size(); ++g) {
        const bool turn = c.segments[g].kind == CircuitSegment::Kind::Turnaround;
        if (g > 0 && (turn || prev_turn)) ++id;
        for (int i = std::max(0, c.segments[g].first); i <= c.segments[g].last && i < n; ++i) {
          piece[i] = id;
        }
        prev_turn = turn;
      }
    }
    per_circuit[ordinal].tangent =
        smooth_tangents(fibre, s, kappa, raw_t, opts.tangent_window, 2.0, piece);
  });
  // A robot's link from circuit c - 1 to circuit c (same surface, same layer, the fibre going on
  // from the same point): the tangent turns there (a turnaround's last, circumferential tangent
  // to the next pass's first: 40 deg on pipe_robot_layup), and the straight move between the two
  // eyes cut 0.76 mm into the clearance of the layer in work (measured by the replay). Link eyes
  // are put before circuit c's first point with the tangent turned from the previous circuit's
  // last tangent in steps of at most kCornerDeg, as insert_corner_eyes does inside a circuit.
  // The previous non-empty circuit of each circuit that links (-1: none, a layer start, another
  // surface, or a gap between the two points).
  std::vector<int> link_from(plan.circuits.size(), -1);
  std::vector<Vec3> last_tangent(plan.circuits.size(), Vec3::Zero());  // read while slots change
  for (std::size_t ci = 0; ci < plan.circuits.size(); ++ci) {
    if (!per_circuit[ci].tangent.empty()) last_tangent[ci] = per_circuit[ci].tangent.back();
  }
  if (true_distance) {
    const std::vector<char> layer_start = layer_start_circuits(plan);
    int prev_ordinal = -1;
    for (std::size_t ci = 0; ci < plan.circuits.size(); ++ci) {
      const Circuit& c = plan.circuits[ci];
      if (c.points.empty()) continue;
      if (prev_ordinal >= 0 && !layer_start[ci] && surface_of[prev_ordinal] == surface_of[ci] &&
          (plan.circuits[prev_ordinal].points.back().position - c.points.front().position).norm() <=
              1e-6) {
        link_from[ci] = prev_ordinal;
      }
      prev_ordinal = static_cast<int>(ci);
    }
  }
  // Prepends the link eyes of circuit `ordinal` (see above) to the arrays of `cm`, as
  // insert_corner_eyes does (fills them when it inserted none); returns the number added.
  auto insert_link_eyes = [&](int ordinal, const Mesh& mesh, const ClosestPointQuery& q,
                              double clearance, const std::vector<double>& s_dense,
                              std::vector<Vec3>* fibre, std::vector<Vec3>* eyes, CircuitMotion* cm,
                              std::vector<int>* first_of) {
    const int from = link_from[ordinal];
    if (from < 0) return 0;
    const Vec3 ta = last_tangent[from].normalized();
    const Vec3 tb = cm->tangent.front().normalized();
    const double ang = std::acos(std::clamp(ta.dot(tb), -1.0, 1.0));
    const int parts = static_cast<int>(std::ceil(ang * kDeg / kCornerDeg));
    if (parts < 2 || std::sin(ang) <= 1e-9) return 0;
    const int n = static_cast<int>(first_of->empty() ? fibre->size() : first_of->size());
    if (first_of->empty()) {
      first_of->resize(n);
      for (int i = 0; i < n; ++i) (*first_of)[i] = i;
      cm->dense = *first_of;
      cm->position = *fibre;
      cm->s = s_dense;
    }
    const Vec3 p = fibre->front();
    std::vector<Vec3> fibre2, eyes2, tangent2;
    std::vector<EyeSolution> sol2;
    for (int k = 1; k < parts; ++k) {
      const double f = static_cast<double>(k) / parts;
      const TurnedEye te = turned_eye(mesh, q, p, ta, tb, ang, f, clearance, cm);
      fibre2.push_back(p);
      eyes2.push_back(te.es.eye);
      tangent2.push_back(te.t);
      sol2.push_back(te.es);
    }
    const int added = parts - 1;
    fibre->insert(fibre->begin(), fibre2.begin(), fibre2.end());
    eyes->insert(eyes->begin(), eyes2.begin(), eyes2.end());
    cm->tangent.insert(cm->tangent.begin(), tangent2.begin(), tangent2.end());
    cm->sol.insert(cm->sol.begin(), sol2.begin(), sol2.end());
    cm->position.insert(cm->position.begin(), fibre2.begin(), fibre2.end());
    cm->dense.insert(cm->dense.begin(), added, 0);
    cm->s.insert(cm->s.begin(), added, s_dense.front());
    for (int& f : *first_of) f += added;
    return added;
  };
  parallel_for_index(static_cast<int>(plan.circuits.size()), [&](int ordinal) {
    const Circuit& c = plan.circuits[ordinal];
    const int n = static_cast<int>(c.points.size());
    if (n == 0) return;
    CircuitMotion& cm = per_circuit[ordinal];
    const int so = surface_of[ordinal];
    const Mesh* surface = so < 0 ? mandrel : surface_meshes[so];
    const ClosestPointQuery* surface_query = so < 0 ? query.get() : surface_queries[so].get();
    try {
      std::vector<Vec3> fibre(n), eyes(n), raw_t(n);
      std::vector<double> s(n);
      for (int i = 0; i < n; ++i) {
        const FibrePoint& fp = c.points[i];
        fibre[i] = fp.position;
        raw_t[i] = fp.tangent;
        s[i] = fp.s;
      }
      const std::vector<Vec3>& tangent = cm.tangent;
      std::vector<EyeSolution>& sol = cm.sol;
      sol.resize(n);
      for (int i = 0; i < n; ++i) {
        const double tn = raw_t[i].norm();
        if (tn > 0.0) {
          const double cosang = std::clamp(tangent[i].dot(raw_t[i]) / tn, -1.0, 1.0);
          cm.max_tangent_change = std::max(cm.max_tangent_change, std::acos(cosang) * kDeg);
        }
        try {
          if (true_distance) {
            const ClearanceEye ce =
                solve_clearance_eye(*surface, *surface_query, fibre[i], tangent[i], eye_clearance);
            sol[i] = eye_solution(ce);
            if (ce.enters) ++cm.fibre_into_mandrel;
          } else {
            sol[i] =
                solve_payout_eye(frame, so < 0 ? env : surface_envelopes[so], fibre[i], tangent[i]);
          }
        } catch (const InputError& e) {
          // The point is named only on failure (no string per point on the hot path).
          throw InputError("circuit " + std::to_string(c.index) + ", point " + std::to_string(i) +
                           ": " + e.what());
        }
        eyes[i] = sol[i].eye;
        cm.max_eye_iterations = std::max(cm.max_eye_iterations, sol[i].iterations);
      }
      int n_eyes = n;
      std::vector<int> first_of;  // dense index -> its entry in the (augmented) arrays
      if (true_distance) {
        n_eyes = insert_corner_eyes(*surface, *surface_query, eye_clearance, s, &fibre, &eyes, &cm,
                                    &first_of);
        n_eyes += insert_link_eyes(ordinal, *surface, *surface_query, eye_clearance, s, &fibre,
                                   &eyes, &cm, &first_of);
      }
      if (query) {
        cm.clearance = check_clearance(*surface_query, eyes);
        // A robot's dense eyes are planned beyond the clearance (eye_clearance): no slack below
        // it; the envelopes' keep chord_tolerance.
        const double slack = true_distance ? 0.0 : opts.chord_tolerance;
        if (cm.clearance.min_distance < m.required_clearance - slack) {
          const Vec3& e = cm.clearance.worst_eye;
          throw InputError(
              "machine.envelope: circuit " + std::to_string(c.index) + ", point " +
              std::to_string(cm.clearance.worst) + ": the eye at (" + num(e.x()) + ", " +
              num(e.y()) + ", " + num(e.z()) + ") mm is " + num(cm.clearance.min_distance) +
              (so < 0 ? " mm from the mandrel" : " mm from the surface it is wound on") +
              ", less than the clearance " + num(m.required_clearance) + " mm (" + env.description +
              ")");
        }
      }
      std::vector<int> forced;
      for (const CircuitSegment& seg : c.segments) {
        for (int k : {seg.first, seg.last}) {
          forced.push_back(first_of.empty() || k < 0 || k >= n ? k : first_of[k]);
        }
      }
      if (true_distance) {
        // The cell moves the eye linearly in X, Y and the positioner angle between targets, so
        // in the mandrel frame it sweeps round the axis, off the Cartesian chord of the eyes (a
        // chord 16 deg round at 100 mm sags 1 mm, into the clearance). The eyes in those
        // coordinates (X, Y, angle x the circuit's largest Y: an arc is never longer) are kept
        // within the tolerance too.
        std::vector<Vec3> axes_path(n_eyes);
        double y_max = 0.0, prev_theta = 0.0;
        for (int i = 0; i < n_eyes; ++i) y_max = std::max(y_max, frame.radius(eyes[i]));
        for (int i = 0; i < n_eyes; ++i) {
          const double raw = frame.angle(eyes[i]);
          const double theta =
              i == 0 ? raw : prev_theta + std::remainder(raw - prev_theta, 2 * kPi);
          prev_theta = theta;
          axes_path[i] = Vec3(frame.axial(eyes[i]), frame.radius(eyes[i]), theta * y_max);
        }
        cm.resampled = resample_by_chord({&fibre, &eyes, &axes_path}, opts.chord_tolerance, forced);
      } else {
        cm.resampled = resample_by_chord({&fibre, &eyes}, opts.chord_tolerance, forced);
      }
    } catch (...) {
      cm.error = std::current_exception();
    }
  });

  // A machine value of state st outside an axis's travel: an error naming the axis, the value,
  // the circuit and point (st.circuit, st.index), and `why` after them.
  auto check_travel = [&](const MachineState& st, const char* why) {
    const double value[4] = {st.a_deg, st.x_mm, st.y_mm, st.b_deg};
    for (int ax = 0; ax < n_axes; ++ax) {
      const double mv = axes[ax]->sign * value[ax] + axes[ax]->offset;
      if (mv < axes[ax]->min || mv > axes[ax]->max) {
        throw InputError("machine.axes." + std::string(names[ax]) + ": axis " + names[ax] +
                         " (letter " + axes[ax]->letter + ") would move to " + num(mv) + " " +
                         units[ax] + ", outside its travel [" + num(axes[ax]->min) + ", " +
                         num(axes[ax]->max) + "], at circuit " + std::to_string(st.circuit) +
                         ", point " + std::to_string(st.index) + why);
      }
    }
  };
  // lathe4: the states [b, e) of circuit c slid along their tangents (monotone_by_payout.h); a
  // slid eye is checked against the travel limits and the clearance as the others were above.
  auto slide_monotone = [&](int b, int e, const ClosestPointQuery* q, const Circuit& c) {
    // A circuit that goes on from the previous one's last point (its dwell arc carries on into
    // this circuit's first pass) keeps the spindle going on across the two.
    const MachineState* before =
        b > 0 && (m.states[b - 1].position - m.states[b].position).norm() <= 1e-6 ? &m.states[b - 1]
                                                                                  : nullptr;
    const MachineState before_copy = before ? *before : MachineState{};
    const MonotoneByPayoutSummary ms =
        monotone_by_payout(frame, &m.states, b, e, before ? &before_copy : nullptr);
    m.payout_slid += ms.slid;
    m.max_payout_slide = std::max(m.max_payout_slide, ms.max_slide);
    if (ms.slid == 0) return;
    for (int i = b; i < e; ++i) {
      const MachineState& st = m.states[i];
      check_travel(st, " (its eye slid along the tangent to keep A and X monotone)");
      m.y.min = std::min(m.y.min, st.y_mm);
      m.y.max = std::max(m.y.max, st.y_mm);
      m.b.min = std::min(m.b.min, st.b_deg);
      m.b.max = std::max(m.b.max, st.b_deg);
      m.free_length.max = std::max(m.free_length.max, st.free_length);
      if (!q) continue;
      const double dist = q->closest(st.eye).distance;
      if (dist < m.required_clearance - opts.chord_tolerance) {
        throw InputError(
            "machine.envelope: circuit " + std::to_string(c.index) + ", point " +
            std::to_string(st.index) + ": the eye slid along its tangent is " + num(dist) +
            (q == query.get() ? " mm from the mandrel" : " mm from the surface it is wound on") +
            ", less than the clearance " + num(m.required_clearance) + " mm");
      }
      if (dist < min_clearance) {
        min_clearance = dist;
        m.min_clearance_circuit = c.index;
        m.min_clearance_index = st.index;
      }
    }
  };
  double laid_before = 0.0;
  bool first = true;
  MachineState prev;
  std::vector<int> circuit_begin;
  for (std::size_t ordinal = 0; ordinal < plan.circuits.size(); ++ordinal) {
    const Circuit& c = plan.circuits[ordinal];
    const int n = static_cast<int>(c.points.size());
    if (n == 0) continue;
    m.dense_points += n;
    CircuitMotion& cm = per_circuit[ordinal];
    if (cm.error) std::rethrow_exception(cm.error);
    m.max_tangent_change = std::max(m.max_tangent_change, cm.max_tangent_change);
    m.max_eye_iterations = std::max(m.max_eye_iterations, cm.max_eye_iterations);
    if (true_distance)
      m.fibre_into_mandrel = std::max(0, m.fibre_into_mandrel) + cm.fibre_into_mandrel;
    const std::vector<Vec3>& tangent = cm.tangent;
    const std::vector<EyeSolution>& sol = cm.sol;
    if (query && cm.clearance.min_distance < min_clearance) {
      min_clearance = cm.clearance.min_distance;
      m.min_clearance_circuit = c.index;
      m.min_clearance_index = cm.clearance.worst;
    }
    const ResampleResult& rs = cm.resampled;
    m.max_chord_deviation = std::max(m.max_chord_deviation, rs.max_deviation);
    const double s0 = c.points.front().s;
    circuit_begin.push_back(static_cast<int>(m.states.size()));
    for (int j : rs.kept) {
      // j indexes the eyes (with a robot's corner eyes inserted), k the plan's dense points.
      const int k = cm.dense.empty() ? j : cm.dense[j];
      const FibrePoint& fp = c.points[k];
      MachineState st;
      st.circuit = c.index;
      st.ordinal = static_cast<int>(ordinal);
      st.index = k;
      st.position = cm.dense.empty() ? fp.position : cm.position[j];
      st.eye = sol[j].eye;
      st.direction = tangent[j];
      st.free_length = sol[j].free_length;
      st.paid_out = laid_before + ((cm.dense.empty() ? fp.s : cm.s[j]) - s0) + st.free_length;
      const double a_raw = -frame.angle(st.eye) * kDeg;
      st.a_deg = first ? a_raw : unwrap_deg(a_raw, prev.a_deg);
      st.x_mm = frame.axial(st.eye);
      st.y_mm = frame.radius(st.eye);
      const Vec3 q = st.eye - frame.origin;
      const Vec3 radial = q - q.dot(frame.d) * frame.d;
      const double rn = radial.norm();
      if (rn > 1e-12) st.radial = radial / rn;
      if (!lathe2) {
        double b_raw = first ? 0.0 : prev.b_deg;
        if (rn > 1e-12) {
          const Vec3 circ = frame.d.cross(radial / rn);
          b_raw = std::atan2(st.direction.dot(circ), st.direction.dot(frame.d)) * kDeg;
        }
        st.b_deg = first ? b_raw : unwrap_deg(b_raw, prev.b_deg);
      }
      check_travel(st, "");
      auto grow = [first](Range* r, double v) {
        if (first) {
          r->min = r->max = v;
        } else {
          r->min = std::min(r->min, v);
          r->max = std::max(r->max, v);
        }
      };
      grow(&m.a, st.a_deg);
      grow(&m.x, st.x_mm);
      grow(&m.y, st.y_mm);
      grow(&m.b, st.b_deg);
      grow(&m.free_length, st.free_length);
      m.states.push_back(st);
      prev = st;
      first = false;
    }
    if (opts.monotone_axes) {
      const int b = circuit_begin.back(), e = static_cast<int>(m.states.size());
      if (opts.kind == "lathe4") {
        // The eyes first slid along their own tangents where A or X would go back (a dwell arc's
        // last eye to its pass's first: export/machine/monotone_by_payout.h); the fit below then
        // changes nothing there.
        const int so = surface_of[ordinal];
        slide_monotone(b, e, so < 0 ? query.get() : surface_queries[so].get(), c);
      }
      std::vector<double> xs(e), as(e);
      for (int i = b; i < e; ++i) {
        xs[i] = m.states[i].x_mm;
        as[i] = m.states[i].a_deg;
      }
      m.max_monotone_change_x =
          std::max(m.max_monotone_change_x, monotone_between_extremes(&xs, b, e));
      m.max_monotone_change_a = std::max(m.max_monotone_change_a, monotone_overall(&as, b, e));
      for (int i = b; i < e; ++i) {
        MachineState& st = m.states[i];
        st.x_mm = xs[i];
        st.a_deg = as[i];
        const double th = -st.a_deg / kDeg;
        st.eye = frame.origin + st.x_mm * frame.d +
                 st.y_mm * (std::cos(th) * frame.u + std::sin(th) * frame.v);
        st.free_length = (st.eye - st.position).norm();
      }
      prev = m.states.back();
    }
    count_circuit_reversals(c, m.states, circuit_begin.back(), static_cast<int>(m.states.size()),
                            &m);
    laid_before += c.points.back().s - s0;
    cm = CircuitMotion{};  // its dense arrays are no longer needed
  }
  if (query && std::isfinite(min_clearance)) m.min_clearance = min_clearance;

  // The feed plan over all moves.
  std::vector<AxisValues> values(m.states.size());
  std::vector<double> cap(m.states.size(), 0.0);
  for (std::size_t i = 0; i < m.states.size(); ++i) {
    const MachineState& st = m.states[i];
    values[i] = {st.a_deg, st.x_mm, st.y_mm, st.b_deg};
    if (i > 0 && opts.max_fibre_speed > 0.0) {
      const MachineState& p = m.states[i - 1];
      const double laid = std::fabs((st.paid_out - st.free_length) - (p.paid_out - p.free_length));
      double len2 = 0.0;
      for (int a = 0; a < n_axes; ++a) len2 += std::pow(values[i][a] - values[i - 1][a], 2);
      if (laid > 0.0) cap[i] = opts.max_fibre_speed * std::sqrt(len2) / laid;
    }
  }
  const std::array<FeedAxis, 4> fa = feed_axes(opts);
  const FeedPlan fp = plan_feed(values, n_axes, fa, cap);
  m.limits = check_axis_limits(values, fp.duration, n_axes, fa);
  m.circuit_time.assign(circuit_begin.size(), 0.0);
  for (std::size_t i = 0; i < m.states.size(); ++i) {
    MachineState& st = m.states[i];
    if (i == 0) continue;
    const MachineState& p = m.states[i - 1];
    const double dur = fp.duration[i];
    st.duration = dur;
    st.t_s = p.t_s + dur;
    double dist2 = 0.0;
    for (int a = 0; a < n_axes; ++a) dist2 += std::pow(values[i][a] - values[i - 1][a], 2);
    if (dur > 0.0) {
      st.feed = m.inverse_time ? 60.0 / dur : 60.0 * std::sqrt(dist2) / dur;
    } else {
      // No motion: the modal feed stays; before any motion a nominal one (a control rejects F0).
      st.feed = p.feed > 0.0 ? p.feed : (m.inverse_time ? 60000.0 : 60.0 * opts.x.max_velocity);
    }
  }
  for (std::size_t k = 0; k < circuit_begin.size(); ++k) {
    const int b = circuit_begin[k];
    const int e =
        k + 1 < circuit_begin.size() ? circuit_begin[k + 1] : static_cast<int>(m.states.size());
    if (e > b) m.circuit_time[k] = m.states[e - 1].t_s - (b > 0 ? m.states[b - 1].t_s : 0.0);
  }
  m.wind_time = m.states.empty() ? 0.0 : m.states.back().t_s;
  return m;
}

}  // namespace windplan
