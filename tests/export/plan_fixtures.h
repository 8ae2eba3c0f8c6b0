#pragma once
// Winding plans made in code from closed-form curves, for the export tests.
#include <cmath>

#include "planner/plan.h"

namespace windplan::test {

/// A point of the exact helix x = R cos(phi), y = R sin(phi), z = c phi on the cylinder of
/// radius R about the z axis, with exact normal, tangent, arc length and winding angle.
inline FibrePoint helix_point(double R, double c, double phi) {
  FibrePoint p;
  const double w = std::sqrt(R * R + c * c);
  p.position = Vec3(R * std::cos(phi), R * std::sin(phi), c * phi);
  p.normal = Vec3(std::cos(phi), std::sin(phi), 0.0);
  p.tangent = Vec3(-R * std::sin(phi), R * std::cos(phi), c) / w;
  p.s = w * phi;
  p.winding_angle = std::atan2(R, std::fabs(c)) * 180.0 / M_PI;
  p.k_n = R / (w * w);  // curvature of the helix, all normal (a geodesic)
  p.k_g = 0.0;
  p.slippage = 0.0;
  return p;
}

/// A plan of `circuits` helices on a cylinder of radius R along z (axis = z, profile = constant R
/// over [z_lo, z_hi]); circuit k spans phi in [2 pi k / circuits, that + turns * 2 pi] with
/// `n` points per circuit. c = R / tan(alpha).
inline WindingPlan helix_plan(double R, double alpha_deg, double turns, int n, int circuits = 1) {
  WindingPlan plan;
  plan.job_name = "helix test";
  const double c = R / std::tan(alpha_deg * M_PI / 180.0);
  const double z_hi = c * (turns * 2.0 * M_PI + 2.0 * M_PI);
  plan.profile.axial = {-10.0, z_hi + 10.0};
  plan.profile.radius = {R, R};
  for (int k = 0; k < circuits; ++k) {
    Circuit ci;
    ci.index = k;
    const double phi0 = 2.0 * M_PI * k / circuits;
    for (int i = 0; i < n; ++i) {
      const double phi = phi0 + turns * 2.0 * M_PI * i / (n - 1);
      FibrePoint p = helix_point(R, c, phi);
      p.s -= std::sqrt(R * R + c * c) * phi0;  // s from the circuit start
      ci.points.push_back(p);
    }
    ci.segments.push_back({CircuitSegment::Kind::Pass, 0, n - 1});
    plan.circuits.push_back(ci);
  }
  plan.metrics.circuits = circuits;
  for (const Circuit& ci : plan.circuits) plan.metrics.fibre_length += ci.points.back().s;
  return plan;
}

}  // namespace windplan::test
