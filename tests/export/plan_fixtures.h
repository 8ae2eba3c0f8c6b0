#pragma once
// Winding plans made in code from closed-form curves, for the export tests.
#include <cmath>

#include "planner/plan/plan.h"

namespace windplan::test {

/// A point of the exact helix x = R cos(phi), y = R sin(phi), z = c phi on the cylinder of
/// radius R about the z axis, with exact normal, tangent, arc length and winding angle.
/// `psi` turns the whole helix about the axis (x = R cos(phi + psi), ...).
inline FibrePoint helix_point(double R, double c, double phi, double psi = 0.0) {
  FibrePoint p;
  const double w = std::sqrt(R * R + c * c);
  const double q = phi + psi;
  p.position = Vec3(R * std::cos(q), R * std::sin(q), c * phi);
  p.normal = Vec3(std::cos(q), std::sin(q), 0.0);
  p.tangent = Vec3(-R * std::sin(q), R * std::cos(q), c) / w;
  p.s = w * phi;
  p.winding_angle = std::atan2(R, std::fabs(c)) * 180.0 / M_PI;
  p.k_n = R / (w * w);  // curvature of the helix, all normal (a geodesic)
  p.k_g = 0.0;
  p.slippage = 0.0;
  return p;
}

/// A plan of `circuits` helices on a cylinder of radius R along z (axis = z, profile = constant R
/// over [-10, z_hi + 10]); circuit k is the helix turned by 2 pi k / circuits about the axis,
/// phi in [0, turns * 2 pi], `n` points per circuit. c = R / tan(alpha).
inline WindingPlan helix_plan(double R, double alpha_deg, double turns, int n, int circuits = 1) {
  WindingPlan plan;
  plan.job_name = "helix test";
  const double c = R / std::tan(alpha_deg * M_PI / 180.0);
  const double z_hi = c * turns * 2.0 * M_PI;
  plan.profile.axial = {-10.0, z_hi + 10.0};
  plan.profile.radius = {R, R};
  for (int k = 0; k < circuits; ++k) {
    Circuit ci;
    ci.index = k;
    const double psi = 2.0 * M_PI * k / circuits;
    for (int i = 0; i < n; ++i) {
      ci.points.push_back(helix_point(R, c, turns * 2.0 * M_PI * i / (n - 1), psi));
    }
    ci.segments.push_back({CircuitSegment::Kind::Pass, 0, n - 1});
    plan.circuits.push_back(ci);
  }
  plan.metrics.circuits = circuits;
  for (const Circuit& ci : plan.circuits) plan.metrics.fibre_length += ci.points.back().s;
  return plan;
}

/// helix_plan(40, 50, 2, 600, 4) as a layup of two layers ("inner": circuits 0-1, "outer": 2-3).
inline WindingPlan two_layer_helix_plan() {
  WindingPlan plan = helix_plan(40, 50, 2, 600, 4);
  plan.layers.resize(2);
  plan.layers[0].name = "inner";
  plan.layers[0].circuit_count = 2;
  plan.layers[1].name = "outer";
  plan.layers[1].first_circuit = 2;
  plan.layers[1].circuit_count = 2;
  return plan;
}

}  // namespace windplan::test
