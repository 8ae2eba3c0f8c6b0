#include "export/kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "export/resample.h"
#include "geometry/errors.h"

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

double Envelope::radius_at(double ax) const {
  if (x.empty()) return 0.0;
  if (ax <= x.front()) return r.front();
  if (ax >= x.back()) return r.back();
  const auto it = std::upper_bound(x.begin(), x.end(), ax);
  const std::size_t i = static_cast<std::size_t>(it - x.begin());
  const double t = (ax - x[i - 1]) / (x[i] - x[i - 1]);
  return (1.0 - t) * r[i - 1] + t * r[i];
}

Envelope make_envelope(const RadiusProfile& mandrel, const EnvelopeOptions& opts) {
  Envelope e;
  const std::string mode = opts.mode();
  if (mode == "free_length") {
    e.fixed_length = true;
    e.free_length = opts.free_length;
    return e;
  }
  if (mode == "profile") {
    for (const auto& xr : opts.profile) {
      e.x.push_back(xr[0]);
      e.r.push_back(xr[1]);
    }
  } else {
    if (mandrel.empty()) {
      throw InputError(
          "machine.envelope: the plan has no mandrel radius profile for 'clearance'; give "
          "machine.envelope.profile or machine.envelope.free_length");
    }
    e.x = mandrel.axial;
    for (double r : mandrel.radius) e.r.push_back(r + opts.clearance);
  }
  for (std::size_t i = 1; i < e.x.size(); ++i) {
    const double dx = e.x[i] - e.x[i - 1];
    if (dx > 0.0) e.max_slope = std::max(e.max_slope, std::fabs(e.r[i] - e.r[i - 1]) / dx);
  }
  return e;
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

Motion compute_motion(const WindingPlan& plan, const MachineOptions& opts) {
  std::string why;
  if (!opts.is_valid(&why)) throw ConfigError("machine: " + why);
  Motion m;
  m.inverse_time = uses_inverse_time(opts.gcode);
  m.layers = plan.layers;
  const AxisFrame frame = make_axis_frame(plan.axis);
  const Envelope env = make_envelope(plan.profile, opts.envelope);
  const bool lathe2 = opts.kind == "lathe2";
  // Machine axes that move (and bound the time): lathe2 drives A and X only.
  const AxisOptions* axes[4] = {&opts.a, &opts.x, &opts.y, &opts.b};
  const char* names[4] = {"A", "X", "Y", "B"};
  const char* units[4] = {"deg", "mm", "mm", "deg"};
  const int n_axes = lathe2 ? 2 : 4;

  double laid_before = 0.0;
  bool first = true;
  MachineState prev;
  for (std::size_t ordinal = 0; ordinal < plan.circuits.size(); ++ordinal) {
    const Circuit& c = plan.circuits[ordinal];
    const int n = static_cast<int>(c.points.size());
    if (n == 0) continue;
    m.dense_points += n;
    std::vector<Vec3> fibre(n), eyes(n);
    std::vector<EyeSolution> sol(n);
    for (int i = 0; i < n; ++i) {
      const FibrePoint& fp = c.points[i];
      try {
        sol[i] = solve_payout_eye(frame, env, fp.position, fp.tangent);
      } catch (const InputError& e) {
        // The point is named only on failure (no string per point on the hot path).
        throw InputError("circuit " + std::to_string(c.index) + ", point " + std::to_string(i) +
                         ": " + e.what());
      }
      fibre[i] = fp.position;
      eyes[i] = sol[i].eye;
      m.max_eye_iterations = std::max(m.max_eye_iterations, sol[i].iterations);
    }
    std::vector<int> forced;
    for (const CircuitSegment& seg : c.segments) {
      forced.push_back(seg.first);
      forced.push_back(seg.last);
    }
    const ResampleResult rs = resample_by_chord({&fibre, &eyes}, opts.chord_tolerance, forced);
    m.max_chord_deviation = std::max(m.max_chord_deviation, rs.max_deviation);
    const double s0 = c.points.front().s;
    for (int k : rs.kept) {
      const FibrePoint& fp = c.points[k];
      MachineState st;
      st.circuit = c.index;
      st.ordinal = static_cast<int>(ordinal);
      st.index = k;
      st.position = fp.position;
      st.eye = sol[k].eye;
      st.direction = fp.tangent.normalized();
      st.free_length = sol[k].free_length;
      st.paid_out = laid_before + (fp.s - s0) + st.free_length;
      const double a_raw = -frame.angle(st.eye) * kDeg;
      st.a_deg = first ? a_raw : unwrap_deg(a_raw, prev.a_deg);
      st.x_mm = frame.axial(st.eye);
      st.y_mm = frame.radius(st.eye);
      if (!lathe2) {
        const Vec3 q = st.eye - frame.origin;
        const Vec3 radial = q - q.dot(frame.d) * frame.d;
        const double rn = radial.norm();
        double b_raw = first ? 0.0 : prev.b_deg;
        if (rn > 1e-12) {
          const Vec3 circ = frame.d.cross(radial / rn);
          b_raw = std::atan2(st.direction.dot(circ), st.direction.dot(frame.d)) * kDeg;
        }
        st.b_deg = first ? b_raw : unwrap_deg(b_raw, prev.b_deg);
      }
      const double value[4] = {st.a_deg, st.x_mm, st.y_mm, st.b_deg};
      for (int ax = 0; ax < n_axes; ++ax) {
        const double mv = axes[ax]->sign * value[ax] + axes[ax]->offset;
        if (mv < axes[ax]->min || mv > axes[ax]->max) {
          throw InputError("machine.axes." + std::string(names[ax]) + ": axis " + names[ax] +
                           " (letter " + axes[ax]->letter + ") would move to " + num(mv) + " " +
                           units[ax] + ", outside its travel [" + num(axes[ax]->min) + ", " +
                           num(axes[ax]->max) + "], at circuit " + std::to_string(c.index) +
                           ", point " + std::to_string(k));
        }
      }
      if (!first) {
        const double prev_value[4] = {prev.a_deg, prev.x_mm, prev.y_mm, prev.b_deg};
        double dur = 0.0, dist2 = 0.0;
        for (int ax = 0; ax < n_axes; ++ax) {
          const double dv = value[ax] - prev_value[ax];
          dur = std::max(dur, std::fabs(dv) / axes[ax]->max_velocity);
          dist2 += dv * dv;
        }
        if (opts.max_fibre_speed > 0.0) {
          const double laid = (st.paid_out - st.free_length) - (prev.paid_out - prev.free_length);
          dur = std::max(dur, std::fabs(laid) / opts.max_fibre_speed);
        }
        // A move without motion still takes a millisecond (keeps F finite).
        dur = std::max(dur, 1e-3);
        st.duration = dur;
        st.t_s = prev.t_s + dur;
        st.feed = m.inverse_time ? 60.0 / dur : 60.0 * std::sqrt(dist2) / dur;
        // A per-minute feed of 0 is an error on most controls; a move without motion keeps the
        // previous (modal) feed.
        if (!m.inverse_time && dist2 == 0.0) st.feed = prev.feed;
      }
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
    laid_before += c.points.back().s - s0;
  }
  m.wind_time = m.states.empty() ? 0.0 : m.states.back().t_s;
  return m;
}

}  // namespace windplan
