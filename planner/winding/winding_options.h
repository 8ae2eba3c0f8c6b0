#pragma once
// The `winding:` job section: how many helices, how many turns, band width, density exponent and
// friction (docs/config.md). Read by the helix planner (planner/winding/helix.h), the plan metrics
// (planner/winding/fibre_metrics.h) and the pipeline (planner/pipeline.h).
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>

#include "geometry/base/format_number.h"

namespace windplan {

/// A number of turns N for messages and reports, e.g. "1", "0.55", "2.5" (%g: six significant
/// digits, whole numbers without a decimal point).
inline std::string format_turns(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", n + 0.0);
  return buf;
}

/// The most circuits a plan may have, given or auto (count; JobLimits::max_circuits).
constexpr int kMaxCircuits = 10000;

/// The largest friction coefficient a job may give (winding.mu): measured fibre-mandrel values are
/// about 0.1-0.5.
constexpr double kMaxMu = 2.0;

struct WindingOptions {
  /// N: turns of each pass about the axis, from one end of the wound region to the other
  /// (turns, finite, > 0; need not be whole: a geodesic pass between the polar openings of a
  /// vessel makes well under one turn, planner/winding/clairaut.h).
  double turns = 2.0;
  /// K: circuits (each circuit = out pass, turnaround, return pass, turnaround); 0 = `auto`:
  /// the circuits needed for full coverage with `band_width` (count, >= 1 or 0).
  int circuits = 0;
  /// Width of the fibre band laid by one pass (mm, > 0).
  double band_width = 10.0;
  /// Density exponent: rho = (g / mean g)^(-beta) with g the girth (dimensionless, [0, 1]).
  /// 0: plain geodesics (most stable); 1: equally spaced helices.
  double beta = 0.0;
  /// Friction coefficient between fibre and mandrel for the slippage check (dimensionless, in
  /// [0, 2]: measured fibre-mandrel values are about 0.1-0.5; above 2 is a typo, not a material).
  double mu = 0.2;
  /// Slippage lambda = |k_g / k_n| the planner may use on purpose (dimensionless, in [0, mu];
  /// 0: geodesic passes only). On shapes of revolution the passes then turn around by friction
  /// at ends whose radius is above the turnaround radius (pipes, cones, stations) instead of
  /// dwelling on pins (planner/winding/friction_winding.h).
  double slippage = 0.0;
  /// Optional axial stations (mm along the spindle axis) that bound the passes instead of the
  /// boundary loops; NaN = the loop. start_station < end_station when both are set.
  double start_station = std::nan("");
  double end_station = std::nan("");
  /// Window of the smoothed finite differences for tangents and curvatures (mm, >= 0;
  /// 0 = band_width).
  double curvature_window = 0.0;
  /// Meridians sampled for the turn spacing (count, >= 4).
  int meridians = 36;
  /// Shapes of revolution (planner/winding/winding_pattern.h): the turnaround radius, i.e. the
  /// Clairaut constant c of the geodesic passes (mm, > 0; NaN: on domes the polar opening radius +
  /// half the band width, elsewhere from `turns`). On domes the passes turn around on the parallel
  /// r = c, tangent to it.
  double turnaround = std::nan("");
  /// Alternative to `turnaround`: the winding angle on the largest parallel (deg, in (0, 90);
  /// NaN: not given). c = R sin(angle).
  double angle = std::nan("");
  /// How far the turnaround radius may move to close the pattern on domes (mm, >= 0; NaN: a
  /// quarter of the band width): outward from `turnaround`, either way from `angle` / `turns`.
  double turnaround_window = std::nan("");
  /// The pattern's skip p (circuit k starts p k / K of a turn after circuit 0; coprime to K;
  /// 0 = auto). `winding.pattern: {circuits: K, skip: p}` sets circuits and skip.
  int skip = 0;
  /// Set by the job loader when the job gives `turns` (on domes the turns then choose c).
  bool turns_given = false;
  /// Stations along the wound length where coverage is measured on the laid bands (count, >= 8).
  int coverage_stations = 12;
  /// `pins: {count, diameter, offset}`: a ring of pins at each end of a friction layer on a bent
  /// tube (planner/winding/tube_friction.h): pins per end (count, >= 0; 0: friction
  /// turnarounds), their diameter (mm, > 0) and the pin circle's distance from the region's end
  /// (mm, >= 0; NaN: half the band width + the diameter).
  int pin_count = 0;
  double pin_diameter = 4.0;
  double pin_offset = std::nan("");

  bool has_start_station() const { return std::isfinite(start_station); }
  bool has_end_station() const { return std::isfinite(end_station); }

  bool is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
      if (why) *why = m;
      return false;
    };
    if (!(turns > 0.0) || !std::isfinite(turns)) {
      return fail("turns must be > 0 (got " + format_turns(turns) + ")");
    }
    if (circuits < 0) {
      return fail("circuits must be >= 1 or auto (got " + std::to_string(circuits) + ")");
    }
    if (!(band_width > 0.0) || !std::isfinite(band_width)) {
      return fail("band_width must be > 0 mm (got " + format_shortest(band_width) + ")");
    }
    if (!(beta >= 0.0 && beta <= 1.0)) {
      return fail("beta must be in [0, 1] (got " + format_shortest(beta) + ")");
    }
    if (!(mu >= 0.0 && mu <= kMaxMu)) {
      return fail("mu must be in [0, 2] (a fibre's friction coefficient on the mandrel; got " +
                  format_shortest(mu) + ")");
    }
    if (!(slippage >= 0.0) || !std::isfinite(slippage)) {
      return fail("slippage must be >= 0 (got " + format_turns(slippage) + ")");
    }
    if (slippage > mu) {
      return fail("slippage " + format_turns(slippage) + " exceeds mu " + format_turns(mu) +
                  ": friction holds the fibre only while |k_g / k_n| <= mu");
    }
    if (!(curvature_window >= 0.0) || !std::isfinite(curvature_window)) {
      return fail("curvature_window must be >= 0 mm");
    }
    if (meridians < 4) return fail("meridians must be >= 4");
    if (std::isfinite(turnaround) && !(turnaround > 0.0)) {
      return fail("turnaround must be > 0 mm (got " + format_shortest(turnaround) + ")");
    }
    if (std::isnan(turnaround) == false && !std::isfinite(turnaround)) {
      return fail("turnaround must be a finite radius in mm");
    }
    if (!std::isnan(angle) && !(angle > 0.0 && angle < 90.0)) {
      return fail("angle must be in (0, 90) deg (got " + format_shortest(angle) + ")");
    }
    if (!std::isnan(turnaround) && !std::isnan(angle)) {
      return fail("give turnaround or angle, not both");
    }
    if (!std::isnan(turnaround_window) &&
        !(turnaround_window >= 0.0 && std::isfinite(turnaround_window))) {
      return fail("turnaround_window must be >= 0 mm");
    }
    if (skip < 0) return fail("pattern skip must be >= 1 (got " + std::to_string(skip) + ")");
    if (circuits > 0 && skip > 0 && (skip >= circuits || std::gcd(skip, circuits) != 1)) {
      return fail("pattern: circuits " + std::to_string(circuits) + " and skip " +
                  std::to_string(skip) + " must be coprime with skip < circuits (gcd " +
                  std::to_string(std::gcd(skip, circuits)) + ")");
    }
    if (coverage_stations < 8 || coverage_stations > 1000) {
      return fail("coverage_stations must be in [8, 1000]");
    }
    if (pin_count < 0) return fail("pins: count must be >= 0");
    if (!(pin_diameter > 0.0) || !std::isfinite(pin_diameter)) {
      return fail("pins: diameter must be > 0 mm");
    }
    if (!std::isnan(pin_offset) && !(pin_offset >= 0.0 && std::isfinite(pin_offset))) {
      return fail("pins: offset must be >= 0 mm");
    }
    if (has_start_station() && has_end_station() && !(start_station < end_station)) {
      return fail("start_station must be < end_station");
    }
    return true;
  }
};

}  // namespace windplan
