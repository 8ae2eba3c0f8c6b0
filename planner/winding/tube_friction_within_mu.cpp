#include "planner/winding/tube_friction_within_mu.h"

#include <algorithm>
#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "planner/winding/fibre_metrics.h"

namespace windplan {

namespace {

constexpr int kMaxReplans = 4;
constexpr double kOnPassDeg = 0.5;  // a point this near a0 to the centre line is on a pass

struct Worst {
  double slippage = 0.0, s = 0.0;
  bool on_pass = false;
  double k_n = 0.0, k_g = 0.0;  ///< measured there (1/mm)
};

// The largest measured |k_g / k_n| of the laid points (pins: of the Pass segments only), where
// it is and whether the fibre there runs at a0 (a pass) or turns (a turnaround).
Worst worst_point(const TubeSurface& line, const TubeFrictionWinding& w, double a0) {
  Worst out;
  for (const Circuit& c : w.circuits) {
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind != CircuitSegment::Kind::Pass) continue;
      for (int i = seg.first; i <= seg.last; ++i) {
        const FibrePoint& q = c.points[i];
        if (!(q.slippage > out.slippage)) continue;
        double s = 0.0, th = 0.0, d = 0.0;
        line.locate(q.position, &s, &th, &d);
        // The direction the angle is measured from: the surface's e1, along P_s (on a bent tube
        // the centre line's tangent).
        const Vec3 e1 = (line.point(s + 0.5, th) - line.point(s - 0.5, th)).normalized();
        const double ang = std::acos(std::min(1.0, std::abs(q.tangent.dot(e1))));
        out = {q.slippage, s, std::abs(ang - a0) * 180.0 / M_PI < kOnPassDeg, q.k_n, q.k_g};
      }
    }
  }
  return out;
}

}  // namespace

TubeFrictionWinding plan_tube_friction_within_mu(const TubeSurface& line, double s0, double s1,
                                                 const Mesh& annulus,
                                                 const std::vector<int>& face_map,
                                                 const SpindleAxis& axis, const WindingOptions& o) {
  double lambda = o.slippage;
  for (int replan = 0;; ++replan) {
    TubeFrictionWinding w = plan_tube_friction(line, s0, s1, annulus, face_map, axis, o, lambda);
    const Worst worst = worst_point(line, w, w.angle_deg * M_PI / 180.0);
    w.measured = worst.slippage;
    w.measured_s = worst.s;
    if (worst.slippage <= o.mu) {
      if (replan > 0) {
        w.summary.termination +=
            "; turnarounds lowered from winding.slippage " + format_turns(o.slippage) + " to " +
            format_fixed(lambda, 4) + " in " + std::to_string(replan) +
            " replans so that the laid points measure within mu " + format_turns(o.mu) + " (max " +
            format_fixed(worst.slippage, 4) + ")";
      }
      return w;
    }
    const std::string where = "the laid fibre measures |k_g/k_n| " +
                              format_fixed(worst.slippage, 3) + " at " + format_fixed(worst.s, 1) +
                              " mm along the centre line, above mu " + format_turns(o.mu);
    const double next = lambda * o.mu / worst.slippage * 0.99;
    if (worst.on_pass || w.pins > 0) {
      throw ConfigError("winding.slippage " + format_turns(o.slippage) + ": " + where +
                        " on a pass held at " + format_fixed(w.angle_deg, 2) + " deg (planned " +
                        format_fixed(w.required, 3) + " at most on the bend; the mandrel's " +
                        "facets add the rest): a higher winding.angle, a gentler bend or a finer " +
                        "mandrel.angular_deflection");
    }
    // Measured straight across (|k_n| below the fibre metrics' straight curvature)
    // yet turning: a flat facet of the mesh where the fitted surface curves a little (a rounded
    // rectangle's flat side beside its corner, which the fit rounds over a few millimetres). No
    // lower slippage holds a turning fibre there.
    if (std::abs(worst.k_n) < kStraightFibreCurvature) {
      throw ConfigError("winding.slippage " + format_turns(o.slippage) + ": " + where +
                        " in a turnaround that turns on a flat side of the mandrel (measured k_n " +
                        format_fixed(worst.k_n * 1000.0, 4) + " /m, k_g " +
                        format_fixed(worst.k_g * 1000.0, 3) + " /m): friction cannot hold a " +
                        "turning fibre on a flat; sections with flat sides are not yet supported " +
                        "for friction turnarounds (an oval or round section instead)");
    }
    if (replan == kMaxReplans) {
      throw ConfigError(
          "winding.slippage " + format_turns(o.slippage) + ": " + where +
          " in a turnaround planned at " + format_fixed(lambda, 3) + " after " +
          std::to_string(replan) + " replans at lower |k_g/k_n|" +
          ": end the region (mandrel.region.centre_line) one turnaround length (about " +
          format_fixed(std::max(w.turnaround_span[0], w.turnaround_span[1]) * 0.5, 1) +
          " mm) inside the straight legs, or a finer mandrel.angular_deflection");
    }
    lambda = next;
  }
}

}  // namespace windplan
