#include "export/machine/monotone_by_payout.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "export/machine/monotone_axes.h"
#include "geometry/base/errors.h"

namespace windplan {
namespace {

constexpr double kDeg = 180.0 / M_PI;

// A state of the fibre point p (unit tangent t) with its eye at free length l, its axes as
// export/machine/kinematics.h defines them (z axis: u = x, v = y).
MachineState state_at(const AxisFrame& f, const Vec3& p, const Vec3& t, double l, double a_near) {
  MachineState s;
  s.position = p;
  s.direction = t;
  s.free_length = l;
  s.eye = p + l * t;
  const double raw = -f.angle(s.eye) * kDeg;
  s.a_deg = a_near + std::remainder(raw - a_near, 360.0);
  s.x_mm = f.axial(s.eye);
  s.y_mm = f.radius(s.eye);
  s.radial = Vec3(s.eye.x(), s.eye.y(), 0.0).normalized();
  const Vec3 circ = f.d.cross(s.radial);
  s.b_deg = std::atan2(t.dot(circ), t.dot(f.d)) * kDeg;
  s.paid_out = 1000.0 + l;
  return s;
}

// A dwell arc on a cylinder of radius r at station 0 (pins hold it), counter-clockwise from 0 to
// 30 deg, its eyes on an envelope of radius r_dwell (raised as the oval canister's tabs raise it:
// 121.9 mm there against 100 mm over the wall), then its pass, a helix at winding angle alpha
// leaving the last pin, its eyes at radius r_pass. A circumferential tangent's eye at radius R is
// acos(r / R) ahead of its point, a helix's too (its line's radial distance is
// sqrt(r^2 + (l sin alpha)^2)), so the pass's first eye is acos(r / r_dwell) - acos(r / r_pass)
// (6.9 deg here) behind the arc's last eye: the spindle would turn back.
struct DwellAndPass {
  double r = 50.0, r_dwell = 80.0, r_pass = 70.0, alpha = 60.0 / kDeg;
  int dwell = 7;  // states of the arc; the last one is the pin the pass leaves
  std::vector<MachineState> states;
  Vec3 pin = Vec3::Zero(), pin_normal = Vec3::UnitX();
};

DwellAndPass dwell_and_pass(const AxisFrame& f) {
  DwellAndPass dp;
  double a = 0.0;
  for (int k = 0; k < dp.dwell; ++k) {
    const double th = k * 5.0 / kDeg;
    const Vec3 n(std::cos(th), std::sin(th), 0.0), c(-std::sin(th), std::cos(th), 0.0);
    const double l = std::sqrt(dp.r_dwell * dp.r_dwell - dp.r * dp.r);
    dp.states.push_back(state_at(f, dp.r * n, c, l, a));
    a = dp.states.back().a_deg;
    dp.pin = dp.r * n;
    dp.pin_normal = n;
  }
  const double th0 = (dp.dwell - 1) * 5.0 / kDeg;
  for (int j = 0; j <= 60; ++j) {
    const double s = 2.0 * j;  // mm along the helix
    const double th = th0 + s * std::sin(dp.alpha) / dp.r;
    const Vec3 n(std::cos(th), std::sin(th), 0.0), c(-std::sin(th), std::cos(th), 0.0);
    const Vec3 p = dp.r * n + s * std::cos(dp.alpha) * Vec3::UnitZ();
    const Vec3 t = std::sin(dp.alpha) * c + std::cos(dp.alpha) * Vec3::UnitZ();
    const double l = std::sqrt(dp.r_pass * dp.r_pass - dp.r * dp.r) / std::sin(dp.alpha);
    dp.states.push_back(state_at(f, p, t, l, a));
    a = dp.states.back().a_deg;
  }
  return dp;
}

// The eye where the machine puts it for axes (a, x, y) (export/program/replay.h's eye_at).
Vec3 eye_of(double a_deg, double x, double y) {
  const double th = -a_deg / kDeg;
  return Vec3(y * std::cos(th), y * std::sin(th), x);
}

TEST(MonotoneByPayout, ThePassAfterARaisedDwellKeepsTheSpindleGoingOnItsOwnTangent) {
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  DwellAndPass dp = dwell_and_pass(f);
  const std::vector<MachineState> natural = dp.states;
  const int first_pass = dp.dwell;
  // Natural eyes: the spindle turns back 6.9 deg at the swing (A decreases over the circuit).
  const double back = std::acos(dp.r / dp.r_dwell) - std::acos(dp.r / dp.r_pass);
  EXPECT_NEAR(natural[first_pass].a_deg - natural[first_pass - 1].a_deg, back * kDeg, 1e-9);

  const MonotoneByPayoutSummary sum =
      monotone_by_payout(f, &dp.states, 0, static_cast<int>(dp.states.size()));
  EXPECT_GT(sum.slid, 0) << sum.brief_report();
  EXPECT_EQ(sum.left, 0) << sum.brief_report();
  for (std::size_t i = 0; i < dp.states.size(); ++i) {
    const MachineState& s = dp.states[i];
    SCOPED_TRACE(i);
    // On its own tangent line, never nearer than its natural eye, axes consistent with the eye.
    EXPECT_LT((s.eye - s.position).cross(s.direction).norm(), 1e-9);
    EXPECT_NEAR((s.eye - s.position).dot(s.direction), s.free_length, 1e-9);
    EXPECT_GE(s.free_length, natural[i].free_length - 1e-12);
    EXPECT_NEAR(s.paid_out - natural[i].paid_out, s.free_length - natural[i].free_length, 1e-9);
    EXPECT_LT((eye_of(s.a_deg, s.x_mm, s.y_mm) - s.eye).norm(), 1e-9);
    const Vec3 circ = f.d.cross(s.radial);
    EXPECT_NEAR(s.b_deg, std::atan2(s.direction.dot(circ), s.direction.dot(f.d)) * kDeg, 1e-9);
    if (i > 0) {
      EXPECT_LE(s.a_deg, dp.states[i - 1].a_deg + 1e-9);  // A one way
      EXPECT_GE(s.x_mm, dp.states[i - 1].x_mm - 1e-9);    // X one way (the pass goes up)
    }
  }
  // Closed form of the pass's first eye: level with the arc's last, so acos(r / r_dwell) ahead of
  // the pin, on the helix's tangent: l sin(alpha) = sqrt(r_dwell^2 - r^2), at radius r_dwell.
  const MachineState& p0 = dp.states[first_pass];
  const double l = std::sqrt(dp.r_dwell * dp.r_dwell - dp.r * dp.r) / std::sin(dp.alpha);
  EXPECT_NEAR(p0.free_length, l, 1e-9);
  EXPECT_NEAR(p0.y_mm, dp.r_dwell, 1e-9);
  EXPECT_NEAR(p0.x_mm, l * std::cos(dp.alpha), 1e-9);
  EXPECT_NEAR(p0.a_deg, dp.states[first_pass - 1].a_deg, 1e-9);
  // Far enough along the pass the natural eyes are ahead again and keep their place.
  EXPECT_LT((dp.states.back().eye - natural.back().eye).norm(), 1e-12);

  // The swing from the arc's last eye to the pass's first, moved linearly in A, X and Y as the
  // machine moves: the free fibre from the last pin to every eye on the way is in the pin's
  // tangent plane's upper half-space, so the pin holds it.
  const MachineState& d = dp.states[first_pass - 1];
  for (int k = 0; k <= 1000; ++k) {
    const double u = k / 1000.0;
    const Vec3 e = eye_of(d.a_deg + u * (p0.a_deg - d.a_deg), d.x_mm + u * (p0.x_mm - d.x_mm),
                          d.y_mm + u * (p0.y_mm - d.y_mm));
    EXPECT_GE((e - dp.pin).dot(dp.pin_normal), -1e-6) << "u " << u;
  }

  // Before: the least-squares fit held A and moved the pass's first eye round the axis, off its
  // tangent and below the pin's tangent plane.
  const int n = static_cast<int>(natural.size());
  std::vector<double> as(n), xs(n);
  for (int i = 0; i < n; ++i) {
    as[i] = natural[i].a_deg;
    xs[i] = natural[i].x_mm;
  }
  monotone_overall(&as, 0, n);
  monotone_between_extremes(&xs, 0, n);
  const Vec3 fitted = eye_of(as[first_pass], xs[first_pass], natural[first_pass].y_mm);
  EXPECT_LT((fitted - dp.pin).dot(dp.pin_normal), -1.0);
}

TEST(MonotoneByPayout, AMonotoneHelixIsLeftAlone) {
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  std::vector<MachineState> st;
  double a = 0.0;
  for (int j = 0; j < 50; ++j) {
    const double s = 3.0 * j, alpha = 0.8, r = 40.0;
    const double th = s * std::sin(alpha) / r;
    const Vec3 n(std::cos(th), std::sin(th), 0.0), c(-std::sin(th), std::cos(th), 0.0);
    st.push_back(state_at(f, r * n + s * std::cos(alpha) * Vec3::UnitZ(),
                          std::sin(alpha) * c + std::cos(alpha) * Vec3::UnitZ(), 70.0, a));
    a = st.back().a_deg;
  }
  const std::vector<MachineState> before = st;
  const MonotoneByPayoutSummary sum = monotone_by_payout(f, &st, 0, 50);
  EXPECT_EQ(sum.slid, 0);
  EXPECT_EQ(sum.left, 0);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(st[i].eye, before[i].eye);
    EXPECT_EQ(st[i].a_deg, before[i].a_deg);
  }
}

TEST(MonotoneByPayout, TheFirstStateIsLevelledWithTheCircuitItGoesOnFrom) {
  // The arc ends one circuit and its pass starts the next: `before` carries the arc's last state.
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  DwellAndPass dp = dwell_and_pass(f);
  const MachineState arc_end = dp.states[dp.dwell - 1];
  std::vector<MachineState> pass(dp.states.begin() + dp.dwell, dp.states.end());
  const int n = static_cast<int>(pass.size());
  std::vector<MachineState> alone = pass;
  EXPECT_EQ(monotone_by_payout(f, &alone, 0, n).slid, 0);  // its own A goes one way
  const MonotoneByPayoutSummary sum = monotone_by_payout(f, &pass, 0, n, &arc_end);
  EXPECT_GT(sum.slid, 0);
  EXPECT_NEAR(pass[0].a_deg, arc_end.a_deg, 1e-9);
  EXPECT_NEAR(pass[0].y_mm, dp.r_dwell, 1e-9);
}

TEST(MonotoneByPayout, ASlideTheWrongWayOrTooLongIsLeftToTheFit) {
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  DwellAndPass dp = dwell_and_pass(f);
  const int n = static_cast<int>(dp.states.size());
  MonotoneByPayoutOptions o;
  o.max_slide = 1.0;  // mm: the swing needs 14.4 mm ((sqrt(80^2-50^2) - sqrt(70^2-50^2)) / sin 60)
  std::vector<MachineState> st = dp.states;
  const MonotoneByPayoutSummary sum = monotone_by_payout(f, &st, 0, n, nullptr, o);
  EXPECT_GT(sum.left, 0);
  EXPECT_EQ(st[dp.dwell].eye, dp.states[dp.dwell].eye);  // not moved
  EXPECT_LE(sum.max_slide, 1.0);
  // A pass eye whose tangent runs backwards round the axis: sliding it turns A farther back.
  st = dp.states;
  MachineState& s = st[dp.dwell];
  s = state_at(f, s.position, Vec3(-s.direction.x(), -s.direction.y(), s.direction.z()),
               s.free_length, s.a_deg);
  const double a_before = s.a_deg;
  if (!(a_before > st[dp.dwell - 1].a_deg)) GTEST_SKIP() << "not behind";
  const MonotoneByPayoutSummary s2 = monotone_by_payout(f, &st, 0, n);
  EXPECT_GE(s2.left, 1);
  EXPECT_EQ(st[dp.dwell].a_deg, a_before);
  o.max_slide = -1.0;
  std::string why;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("max_slide"), std::string::npos);
  EXPECT_THROW(monotone_by_payout(f, &st, 0, n, nullptr, o), ConfigError);
}

}  // namespace
}  // namespace windplan
