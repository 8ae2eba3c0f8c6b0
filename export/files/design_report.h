#pragma once
// design.md: what the `design:` section decided and checked (planner/layup/design.h), written
// beside report.md by `windplan run` for a job with a `design:` section:
//   the load (pressure, burst factor, allowable fibre-direction stress), the ply's constants,
//   the netting sizing (when the job was sized: radius, angle, required and wound thicknesses,
//   layers), the netting burst pressure of the wound laminate layer by layer (each layer's
//   measured angle and cylinder thickness: axial and hoop capacity, the burst pressure once it is
//   laid), the dome thickness model and turnaround stagger, time and cost per layer (wind time,
//   fibre and resin mass) with the resin pot-life check, and the structural model's files.
#include <string>
#include <vector>

#include "planner/layup/design.h"
#include "planner/plan_layup.h"

namespace windplan {

/// "" when the pot life is not given or the wind time fits it; else the warning (one line).
std::string pot_life_warning(const DesignOptions& design, double wind_time_s);

/// design.md (header comment). `layer_times` per layer (s), as layer_wind_times gives them.
std::string design_markdown(const DesignOptions& design, bool sized, const DesignLayup& sizing,
                            const LayupResult& layup, const std::vector<double>& layer_times,
                            bool model_written);

}  // namespace windplan
