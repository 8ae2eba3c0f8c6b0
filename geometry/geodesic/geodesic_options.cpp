#include "geometry/geodesic/geodesic_options.h"

#include <cmath>
#include <sstream>

namespace windplan {

const char* to_string(GeodesicTermination t) {
  switch (t) {
    case GeodesicTermination::Converged:
      return "converged";
    case GeodesicTermination::ObjectiveStalled:
      return "objective_stalled";
    case GeodesicTermination::MaxIterations:
      return "max_iterations";
    case GeodesicTermination::MaxReroutes:
      return "max_reroutes";
    case GeodesicTermination::LineSearchFailed:
      return "line_search_failed";
  }
  return "unknown";
}

bool GeodesicOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (!(gradient_tolerance > 0.0)) return fail("gradient_tolerance must be > 0");
  if (!(objective_tolerance >= 0.0)) return fail("objective_tolerance must be >= 0");
  if (max_iterations < 1) return fail("max_iterations must be >= 1");
  if (max_reroutes < 0) return fail("max_reroutes must be >= 0");
  if (lbfgs_memory < 1) return fail("lbfgs_memory must be >= 1");
  if (max_windows < 0) return fail("max_windows must be >= 0 (0: no limit)");
  if (!(constraint_tolerance > 0.0)) return fail("constraint_tolerance must be > 0");
  if (max_outer_iterations < 1) return fail("max_outer_iterations must be >= 1");
  if (!(penalty_weight >= 0.0) || !std::isfinite(penalty_weight))
    return fail("penalty_weight must be finite and >= 0");
  return true;
}

std::string GeodesicSummary::brief_report() const {
  std::ostringstream s;
  s.precision(10);
  s << "geodesic: " << to_string(termination) << ", length " << initial_length << " -> "
    << final_length << ", " << iterations << " iterations, " << evaluations << " evaluations, "
    << reroutes << " reroutes, " << lifts << " lifts, " << pinned_vertices << " pinned vertices";
  if (outer_iterations > 0) s << ", residual " << constraint_residual;
  s.precision(4);
  s << ", " << time_ms << " ms";
  if (!message.empty()) s << " (" << message << ")";
  return s.str();
}

}  // namespace windplan
