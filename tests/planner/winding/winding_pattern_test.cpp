// Pattern selection (planner/winding/winding_pattern.h): closing patterns against the closed form
// of the hemispherical capsule, the coverage count, and the keys a job gives.
#include "planner/winding/winding_pattern.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "geometry/base/errors.h"
#include "planner/job/job.h"
#include "planner/winding/clairaut_pass.h"
#include "tests/planner/winding_fixtures.h"

namespace windplan {
namespace {

constexpr double kR = 100, kL = 300, kOpen = 30;

// Phi(c) of the capsule with hemispherical domes in closed form.
double capsule_phi(double c) { return M_PI + kL * c / (kR * std::sqrt(kR * kR - c * c)); }

double mod2pi(double a) {
  a = std::fmod(a, 2 * M_PI);
  return a < 0 ? a + 2 * M_PI : a;
}

const std::vector<Vec2>& capsule() {
  static const std::vector<Vec2> m = test::capsule_meridian(kR, kL, kOpen, 4000, 10);
  return m;
}

TEST(WindingPattern, DefaultTurnaroundIsTheOpeningPlusHalfTheBand) {
  WindingOptions o;
  o.band_width = 16;
  const PatternProblem pr = pattern_problem(capsule(), o);
  EXPECT_TRUE(pr.domes);
  EXPECT_NEAR(pr.requested_c, kOpen + 8, 1e-9);
  EXPECT_EQ(pr.requested_by, "winding.turnaround");
  EXPECT_NEAR(pr.c_lo, kOpen + 8, 1e-9);
  EXPECT_NEAR(pr.c_hi, kOpen + 8 + 4, 1e-9);  // a quarter band outward
}

TEST(WindingPattern, AutoPatternClosesAndCoversWithTheFewestCircuits) {
  WindingOptions o;
  o.band_width = 16;
  const PatternProblem pr = pattern_problem(capsule(), o);
  const PatternCandidate k = choose_pattern(pr, o);
  EXPECT_EQ(std::gcd(k.skip, k.circuits), 1);
  EXPECT_GE(k.c, pr.c_lo);
  EXPECT_LE(k.c, pr.c_hi);
  // Closes: 2 Phi(c) = 2 pi p / K modulo 2 pi, with the closed-form Phi.
  const double adv = mod2pi(2.0 * capsule_phi(k.c));
  const double target = 2 * M_PI * k.skip / k.circuits;
  EXPECT_NEAR(std::remainder(adv - target, 2 * M_PI), 0.0, 1e-4);
  // Full nominal cover with the fewest circuits of any closing candidate.
  const double ca = std::sqrt(1 - std::pow(k.c / kR, 2));
  EXPECT_GE(k.circuits * 16.0, 2 * M_PI * kR * ca);
  for (const PatternCandidate& other : pattern_candidates(pr)) {
    if (other.circuits < k.circuits) {
      EXPECT_FALSE(other.full_cover()) << other.name();
    }
  }
  EXPECT_NEAR(k.overlap, 16.0 - 2 * M_PI * kR * ca / k.circuits, 1e-12);
  EXPECT_TRUE(k.full_cover());
}

TEST(WindingPattern, EveryCandidateCloses) {
  WindingOptions o;
  o.band_width = 16;
  const PatternProblem pr = pattern_problem(capsule(), o);
  const std::vector<PatternCandidate> all = pattern_candidates(pr);
  ASSERT_GT(all.size(), 5u);
  for (const PatternCandidate& k : all) {
    EXPECT_EQ(std::gcd(k.skip, k.circuits), 1);
    const double target = 2 * M_PI * k.skip / k.circuits;
    EXPECT_NEAR(std::remainder(2.0 * capsule_phi(k.c) - target, 2 * M_PI), 0.0, 1e-4) << k.name();
  }
  // Full cover first, then fewer circuits.
  for (std::size_t i = 1; i < all.size(); ++i) {
    if (all[i - 1].full_cover() == all[i].full_cover()) {
      EXPECT_LE(all[i - 1].circuits, all[i].circuits);
    } else {
      EXPECT_TRUE(all[i - 1].full_cover());
    }
  }
}

TEST(WindingPattern, GivenPatternAndItsErrors) {
  WindingOptions o;
  o.band_width = 16;
  const PatternProblem auto_pr = pattern_problem(capsule(), o);
  // The last candidate of the table, asked for by K and p.
  const PatternCandidate want = pattern_candidates(auto_pr).back();
  o.circuits = want.circuits;
  o.skip = want.skip;
  const PatternProblem pr = pattern_problem(capsule(), o);
  const PatternCandidate k = choose_pattern(pr, o);
  EXPECT_EQ(k.circuits, want.circuits);
  EXPECT_EQ(k.skip, want.skip);
  EXPECT_NEAR(k.c, want.c, 1e-9);
  EXPECT_NEAR(std::remainder(2.0 * capsule_phi(k.c) - 2 * M_PI * k.skip / k.circuits, 2 * M_PI),
              0.0, 1e-4);
  // Not coprime.
  o.skip = 0;
  WindingOptions bad = o;
  bad.circuits = 36;
  bad.skip = 4;
  std::string why;
  EXPECT_FALSE(bad.is_valid(&why));
  EXPECT_NE(why.find("coprime"), std::string::npos);
  // No turnaround in a zero window closes K = 37, p = 5 (unless by chance exactly).
  WindingOptions none = o;
  none.circuits = 37;
  none.skip = 5;
  none.turnaround_window = 0.0;
  const PatternProblem narrow = pattern_problem(capsule(), none);
  try {
    choose_pattern(narrow, none);
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("winding.pattern"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nearest"), std::string::npos) << e.what();
  }
}

TEST(WindingPattern, TurnaroundOutsideTheDomesIsRefusedNamingTheKey) {
  WindingOptions o;
  o.band_width = 16;
  for (double c : {20.0, 100.0, 150.0}) {
    o.turnaround = c;
    try {
      pattern_problem(capsule(), o);
      ADD_FAILURE() << "c = " << c;
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("winding.turnaround = ", 0), 0u) << e.what();
    }
  }
  o.turnaround = std::nan("");
  o.angle = 20.0;
  const PatternProblem pr = pattern_problem(capsule(), o);
  EXPECT_NEAR(pr.requested_c, kR * std::sin(20.0 * M_PI / 180), 1e-9);
  EXPECT_LT(pr.c_lo, pr.requested_c);  // the angle may move either way
}

TEST(WindingPattern, TurnsChooseTheTurnaroundOnDomes) {
  WindingOptions o;
  o.band_width = 16;
  o.turns_given = true;
  o.turns = 0.7;
  const PatternProblem pr = pattern_problem(capsule(), o);
  EXPECT_NEAR(capsule_phi(pr.requested_c), 2 * M_PI * 0.7, 1e-4);
  o.turns = 0.3;  // fewer than a great circle from pole to pole: impossible
  EXPECT_THROW(pattern_problem(capsule(), o), ConfigError);
}

TEST(WindingPattern, DwellEndsCloseAnyPattern) {
  // A pipe: both ends dwell; N turns fix c; the dwells close (K, p).
  const std::vector<Vec2> pipe{{0, 50}, {500, 50}};
  WindingOptions o;
  o.band_width = 12;
  o.turns = 3;
  const PatternProblem pr = pattern_problem(pipe, o);
  EXPECT_FALSE(pr.domes);
  EXPECT_NEAR(clairaut_pass_angle(pipe, pr.requested_c), 6 * M_PI, 1e-9);
  const PatternCandidate k = choose_pattern(pr, o);
  EXPECT_GT(k.dwell[0], 0.0);
  EXPECT_GT(k.dwell[1], 0.0);
  EXPECT_NEAR(std::remainder(k.advance - 2 * M_PI * k.skip / k.circuits, 2 * M_PI), 0.0, 1e-12);
  // More turns than the pipe allows between dwell ends is not an error here: it is reported
  // as unreachable (the pipeline falls back to the geodesic core and warns).
  const std::vector<Vec2> cone{{0, 60}, {400, 40}};
  o.turns = 50;
  const PatternProblem far = pattern_problem(cone, o);
  EXPECT_FALSE(far.reachable);
  EXPECT_NE(far.why.find("at most"), std::string::npos);
}

TEST(WindingPattern, JobKeys) {
  const std::string head = "mandrel: {source: pipe, pipe: {radius: 50, length: 500}}\n";
  Job j = load_job_from_string(head + "winding: {pattern: {circuits: 13, skip: 5}}\n", "j.yaml");
  EXPECT_EQ(j.winding.circuits, 13);
  EXPECT_EQ(j.winding.skip, 5);
  j = load_job_from_string(head +
                               "winding: {pattern: auto, turnaround: 30, "
                               "turnaround_window: 2}\n",
                           "j.yaml");
  EXPECT_EQ(j.winding.circuits, 0);
  EXPECT_EQ(j.winding.turnaround, 30);
  EXPECT_FALSE(j.winding.turns_given);
  for (const char* bad :
       {"winding: {pattern: {circuits: 12, skip: 4}}\n", "winding: {pattern: sometimes}\n",
        "winding: {pattern: auto, circuits: 3}\n", "winding: {turnaround: 30, angle: 20}\n",
        "winding: {angle: 95}\n", "winding: {coverage_stations: 3}\n"}) {
    try {
      load_job_from_string(head + bad, "j.yaml");
      ADD_FAILURE() << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("j.yaml"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("winding"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace windplan
