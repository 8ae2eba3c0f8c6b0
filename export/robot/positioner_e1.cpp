#include "export/robot/positioner_e1.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "export/machine/monotone_axes.h"
#include "geometry/base/errors.h"

namespace windplan {

namespace {

/// [begin, end) of every circuit's states (consecutive states of one ordinal).
std::vector<std::pair<int, int>> circuit_ranges(const Motion& motion) {
  std::vector<std::pair<int, int>> r;
  const int n = static_cast<int>(motion.states.size());
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && motion.states[j].ordinal == motion.states[i].ordinal) ++j;
    r.push_back({i, j});
    i = j;
  }
  return r;
}

/// One moving average of v[b..e) over the states within +-w s (t_s): windows [lo, hi] whose ends
/// never move back, so a monotone v stays monotone (summed directly, relative to v[b], and the
/// rounding of the sums kept from undoing it by a running max or min in the direction `up`).
void moving_average(const Motion& motion, std::vector<double>* v, int b, int e, double w, bool up) {
  const double base = (*v)[b];
  std::vector<double> out(e - b);
  int lo = b, hi = b;
  for (int i = b; i < e; ++i) {
    const double t = motion.states[i].t_s;
    while (lo < i && motion.states[lo].t_s < t - w) ++lo;
    if (hi < i) hi = i;
    while (hi + 1 < e && motion.states[hi + 1].t_s <= t + w) ++hi;
    double sum = 0.0;
    for (int k = lo; k <= hi; ++k) sum += (*v)[k] - base;
    out[i - b] = base + sum / (hi - lo + 1);
    if (i > b) {
      out[i - b] = up ? std::max(out[i - b], out[i - b - 1]) : std::min(out[i - b], out[i - b - 1]);
    }
  }
  for (int i = b; i < e; ++i) (*v)[i] = out[i - b];
}

}  // namespace

bool PositionerE1Options::is_valid(std::string* why) const {
  if (!(smoothing >= 0.0) || !std::isfinite(smoothing)) {
    if (why) *why = "smoothing must be >= 0 s";
    return false;
  }
  return true;
}

std::string PositionerE1::brief_report() const {
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "positioner E1: %d reversals inside passes (E1 = A would make %d), max %d per "
                "circuit, the arm takes up to %.2f deg about the E1 axis",
                reversals_in_passes, a_reversals_in_passes, max_reversals_per_circuit, max_offset);
  return buf;
}

int reversals_in_passes(const Motion& motion, const WindingPlan& plan, const std::vector<double>& v,
                        int* max_per_circuit) {
  int total = 0, worst = 0;
  for (const auto& [b, e] : circuit_ranges(motion)) {
    const MachineState& s0 = motion.states[b];
    const Circuit* c = s0.ordinal >= 0 && s0.ordinal < static_cast<int>(plan.circuits.size())
                           ? &plan.circuits[s0.ordinal]
                           : nullptr;
    auto in_pass = [&](int k) {
      if (!c) return false;
      for (const CircuitSegment& seg : c->segments) {
        if (seg.kind == CircuitSegment::Kind::Pass && k > seg.first && k < seg.last) return true;
      }
      return false;
    };
    int count = 0, dir = 0, last = b;
    for (int i = b + 1; i < e; ++i) {
      const double d = v[i] - v[i - 1];
      if (std::fabs(d) < 1e-9) continue;
      const int s = d > 0 ? 1 : -1;
      if (dir != 0 && s != dir && in_pass(motion.states[last].index)) ++count;
      dir = s;
      last = i;
    }
    total += count;
    worst = std::max(worst, count);
  }
  if (max_per_circuit) *max_per_circuit = worst;
  return total;
}

PositionerE1 fit_positioner_e1(const Motion& motion, const WindingPlan& plan,
                               const PositionerE1Options& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("positioner E1: " + why);
  PositionerE1 r;
  const int n = static_cast<int>(motion.states.size());
  std::vector<double> a(n);
  for (int i = 0; i < n; ++i) a[i] = motion.states[i].a_deg;
  r.e1 = a;
  for (const auto& [b, e] : circuit_ranges(motion)) {
    const bool up = r.e1[e - 1] - r.e1[b] >= 0.0;
    isotonic_fit(&r.e1, b, e, up);
    if (options.smoothing > 0.0) {
      for (int k = 0; k < 2; ++k) moving_average(motion, &r.e1, b, e, options.smoothing, up);
    }
  }
  for (int i = 0; i < n; ++i) r.max_offset = std::max(r.max_offset, std::fabs(r.e1[i] - a[i]));
  r.a_reversals_in_passes = reversals_in_passes(motion, plan, a);
  r.reversals_in_passes = reversals_in_passes(motion, plan, r.e1, &r.max_reversals_per_circuit);
  return r;
}

}  // namespace windplan
