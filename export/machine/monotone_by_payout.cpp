#include "export/machine/monotone_by_payout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;
// deg and mm: a state level with the previous one to this is not behind it (the closed forms
// below land on the previous value up to rounding).
constexpr double kLevel = 1e-9;
// mm: X steps back smaller than this are noise (below the G-code's 4 decimals).
constexpr double kXNoise = 1e-3;
// X is levelled by a slide only along a tangent at least 10 deg from circumferential.
constexpr double kMinAxialForX = 0.17364817766693033;

double unwrap_deg(double raw, double near) { return near + std::remainder(raw - near, 360.0); }

}  // namespace

bool MonotoneByPayoutOptions::is_valid(std::string* why) const {
  if (!(max_slide >= 0.0) || !std::isfinite(max_slide)) {
    if (why) *why = "max_slide must be a finite number >= 0 (mm)";
    return false;
  }
  return true;
}

std::string MonotoneByPayoutSummary::brief_report() const {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "monotone by payout: %d eyes slid along their tangent (largest %.3f mm), %d left "
                "to the least-squares fit",
                slid, max_slide, left);
  return buf;
}

MonotoneByPayoutSummary monotone_by_payout(const AxisFrame& frame,
                                           std::vector<MachineState>* states, int begin, int end,
                                           const MachineState* before,
                                           const MonotoneByPayoutOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("monotone_by_payout: " + why);
  MonotoneByPayoutSummary sum;
  std::vector<MachineState>& st = *states;
  if (end - begin < 2) return sum;  // one state has no direction to keep
  // The directions the axes must keep, from the unslid values (as monotone_axes.h takes them):
  // A its net change, X up to its first extreme, back to the other one, then on to the end.
  const double sa = st[end - 1].a_deg >= st[begin].a_deg ? 1.0 : -1.0;
  int i_max = begin, i_min = begin;
  for (int i = begin + 1; i < end; ++i) {
    if (st[i].x_mm > st[i_max].x_mm) i_max = i;
    if (st[i].x_mm < st[i_min].x_mm) i_min = i;
  }
  const int e1 = std::min(i_max, i_min), e2 = std::max(i_max, i_min);
  const double s_first = e1 == i_max ? 1.0 : -1.0;
  auto x_sign = [&](int i) { return i <= e1 ? s_first : (i <= e2 ? -s_first : s_first); };

  for (int i = before ? begin : begin + 1; i < end; ++i) {
    MachineState& s = st[i];
    const MachineState& p = i > begin ? st[i - 1] : *before;
    // Into the first state (from `before`), X keeps the way it goes on from there.
    const double sx = x_sign(i > begin ? i : begin + 1);
    auto behind_a = [&](double a) { return sa * (a - p.a_deg) < -kLevel; };
    // X's steps back below kXNoise, and a dwell's (a circumferential tangent, whose line barely
    // moves in X: levelling a 0.005 mm step there slid the eye 100 mm out), stay with the fit.
    const bool back_a = behind_a(s.a_deg);
    const bool back_x =
        sx * (s.x_mm - p.x_mm) < -kXNoise && std::fabs(s.direction.dot(frame.d)) >= kMinAxialForX;
    if (!back_a && !back_x) continue;
    const Vec3& t = s.direction;
    const double l0 = s.free_length;
    auto a_at = [&](const Vec3& e) { return unwrap_deg(-frame.angle(e) * kDeg, s.a_deg); };
    double l = l0;
    bool ok = true;
    if (back_a) {
      // The tangent line crosses the previous eye's meridian half-plane (angle -A_prev) at la.
      const double th = -p.a_deg / kDeg;
      const Vec3 dir = std::cos(th) * frame.u + std::sin(th) * frame.v;
      Vec3 q0 = s.position - frame.origin;
      q0 -= q0.dot(frame.d) * frame.d;
      const Vec3 w = t - t.dot(frame.d) * frame.d;
      const double cw = dir.cross(w).dot(frame.d);
      const double la = std::fabs(cw) > 1e-12 ? -dir.cross(q0).dot(frame.d) / cw : -1.0;
      ok = la > l0 && dir.dot(q0 + la * w) > 0.0;
      l = std::max(l, la);
    }
    if (back_x) {
      // The tangent line crosses the previous eye's station at lx.
      const double td = t.dot(frame.d);
      const double lx = std::fabs(td) > 1e-12 ? (p.x_mm - frame.axial(s.position)) / td : -1.0;
      ok = ok && lx > l0;
      l = std::max(l, lx);
    }
    const Vec3 e = s.position + l * t;
    // Landing on the previous value is up to rounding; a slide the wrong way (the line crosses
    // the bound behind the eye), one that puts X farther behind than it was (beyond the noise),
    // or one too long is left to the fit.
    ok = ok && l - l0 <= options.max_slide && !behind_a(a_at(e)) &&
         sx * (frame.axial(e) - p.x_mm) >= std::min(0.0, sx * (s.x_mm - p.x_mm)) - kXNoise;
    if (!ok) {
      ++sum.left;
      continue;
    }
    const Vec3 q = e - frame.origin;
    const Vec3 radial = q - q.dot(frame.d) * frame.d;
    const double rn = radial.norm();
    if (!(rn > 1e-12)) {
      ++sum.left;
      continue;
    }
    s.eye = e;
    s.a_deg = a_at(e);
    s.x_mm = frame.axial(e);
    s.y_mm = rn;
    s.radial = radial / rn;
    const Vec3 circ = frame.d.cross(s.radial);
    s.b_deg = unwrap_deg(std::atan2(t.dot(circ), t.dot(frame.d)) * kDeg, s.b_deg);
    s.paid_out += l - l0;
    s.free_length = l;
    ++sum.slid;
    if (l - l0 > sum.max_slide) {
      sum.max_slide = l - l0;
      sum.worst = i;
    }
  }
  return sum;
}

}  // namespace windplan
