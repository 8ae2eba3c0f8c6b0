#pragma once
// The `winding:` job section: how many helices, how many turns, band width, density exponent and
// friction (docs/config.md). Read by the helix planner (planner/helix.h), the plan metrics
// (planner/fibre_metrics.h) and the pipeline (planner/pipeline.h).
#include <cmath>
#include <cstdio>
#include <string>

namespace windplan {

/// A number of turns N for messages and reports, e.g. "1", "0.55", "2.5" (%g: six significant
/// digits, whole numbers without a decimal point).
inline std::string format_turns(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", n + 0.0);
  return buf;
}

struct WindingOptions {
  /// N: turns of each pass about the axis, from one end of the wound region to the other
  /// (turns, finite, > 0; need not be whole: a geodesic pass between the polar openings of a
  /// vessel makes well under one turn, planner/clairaut.h).
  double turns = 2.0;
  /// K: circuits (each circuit = out pass, turnaround, return pass, turnaround); 0 = `auto`:
  /// the circuits needed for full coverage with `band_width` (count, >= 1 or 0).
  int circuits = 0;
  /// Width of the fibre band laid by one pass (mm, > 0).
  double band_width = 10.0;
  /// Density exponent: rho = (g / mean g)^(-beta) with g the girth (dimensionless, [0, 1]).
  /// 0: plain geodesics (most stable); 1: equally spaced helices.
  double beta = 0.0;
  /// Friction coefficient between fibre and mandrel for the slippage check (dimensionless, >= 0).
  double mu = 0.2;
  /// Optional axial stations (mm along the spindle axis) that bound the passes instead of the
  /// boundary loops; NaN = the loop. start_station < end_station when both are set.
  double start_station = std::nan("");
  double end_station = std::nan("");
  /// Window of the smoothed finite differences for tangents and curvatures (mm, >= 0;
  /// 0 = band_width).
  double curvature_window = 0.0;
  /// Meridians sampled for the turn spacing (count, >= 4).
  int meridians = 36;

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
      return fail("band_width must be > 0 mm (got " + std::to_string(band_width) + ")");
    }
    if (!(beta >= 0.0 && beta <= 1.0)) {
      return fail("beta must be in [0, 1] (got " + std::to_string(beta) + ")");
    }
    if (!(mu >= 0.0) || !std::isfinite(mu)) {
      return fail("mu must be >= 0 (got " + std::to_string(mu) + ")");
    }
    if (!(curvature_window >= 0.0) || !std::isfinite(curvature_window)) {
      return fail("curvature_window must be >= 0 mm");
    }
    if (meridians < 4) return fail("meridians must be >= 4");
    if (has_start_station() && has_end_station() && !(start_station < end_station)) {
      return fail("start_station must be < end_station");
    }
    return true;
  }
};

}  // namespace windplan
