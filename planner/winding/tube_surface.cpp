#include "planner/winding/tube_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace windplan {

ConstantAngleDemand TubeSurface::demand(double s0, double s1, double a) const {
  // Sampled every 2 mm along (at least 64 stations) and every 0.25 deg around: the fitted
  // surfaces are smooth on the scale of a band.
  ConstantAngleDemand d;
  d.min_k_n = std::numeric_limits<double>::infinity();
  d.s = s0;
  const int ns = std::max(64, static_cast<int>(std::ceil((s1 - s0) / 2.0)));
  const int nt = 1440;
  for (int i = 0; i <= ns; ++i) {
    const double s = s0 + (s1 - s0) * i / ns;
    const int pc = piece_at(s);
    for (int k = 0; k < nt; ++k) {
      const double th = -M_PI + 2.0 * M_PI * (k + 1) / nt;
      const Rates q = rates(pc, s, th, a);
      d.min_k_n = std::min(d.min_k_n, q.k_n);
      // Where both vanish (a straight line on a flat side: a geodesic, held without friction)
      // the demand reads 0; a concave direction (k_n < -kFlatCurvature) bridges.
      const double lam = std::abs(q.k_n) <= kFlatCurvature && std::abs(q.w) <= kFlatCurvature ? 0.0
                         : q.k_n > 0.0 ? std::abs(q.w) / q.k_n
                                       : std::numeric_limits<double>::infinity();
      if (lam > d.slippage) {
        d.slippage = lam;
        d.s = s;
        d.theta_outside = th;
      }
    }
  }
  return d;
}

}  // namespace windplan
