#include "export/machine/tangent_smoothing.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace windplan {
namespace {

TEST(TangentSmoothing, NoisyHelixTangentsComeBackExact) {
  // A helix (R = 50, pitch 20 mm/rad) sampled every 0.5 mm, its tangents tilted by +-2 deg noise:
  // the fit over the points gives the tangent back within its O((w kappa)^2) bias.
  const double R = 50, c = 20, w = std::hypot(R, c);
  std::vector<Vec3> p, t, exact;
  std::vector<double> s, k;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-0.035, 0.035);
  for (int i = 0; i <= 2000; ++i) {
    const double phi = 0.5 * i / w;
    p.emplace_back(R * std::cos(phi), R * std::sin(phi), c * phi);
    exact.push_back(Vec3(-R * std::sin(phi), R * std::cos(phi), c) / w);
    t.push_back((exact.back() + Vec3(noise(rng), noise(rng), noise(rng))).normalized());
    s.push_back(0.5 * i);
    k.push_back(R / (w * w));
  }
  const std::vector<Vec3> out = smooth_tangents(p, s, k, t, 15.0);
  double worst = 0, worst_raw = 0;
  for (int i = 40; i <= 1960; ++i) {
    worst = std::max(worst, std::acos(std::min(1.0, out[i].dot(exact[i]))));
    worst_raw = std::max(worst_raw, std::acos(std::min(1.0, t[i].dot(exact[i]))));
  }
  EXPECT_LT(worst, 5e-3);
  EXPECT_GT(worst_raw, 0.02);
  // A window of 0 returns the tangents unchanged; pieces keep windows apart.
  EXPECT_EQ(smooth_tangents(p, s, k, t, 0.0)[7], t[7]);
  std::vector<int> piece(p.size(), 0);
  for (std::size_t i = 1000; i < p.size(); ++i) piece[i] = 1;
  const std::vector<Vec3> split = smooth_tangents(p, s, k, t, 15.0, 2.0, piece);
  EXPECT_EQ(split[999], t[999]);  // at a piece end the symmetric window is empty
  EXPECT_LT(std::acos(std::min(1.0, split[960].dot(exact[960]))), 5e-3);
}

}  // namespace
}  // namespace windplan
