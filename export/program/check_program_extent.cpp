#include "export/program/check_program_extent.h"

#include <algorithm>
#include <cmath>

#include "export/machine/eye_envelope.h"
#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

bool ProgramExtentOptions::is_valid(std::string* why) const {
  if (!(std::isfinite(max_travel_mm) && max_travel_mm > 0.0)) {
    if (why) *why = "max_travel_mm must be > 0 mm";
    return false;
  }
  return true;
}

ProgramExtent check_program_extent(const GcodeProgram& program, const WindingPlan& plan,
                                   const Mesh& mandrel, const MachineOptions& machine,
                                   const std::string& name, const ProgramExtentOptions& options) {
  if (std::string why; !options.is_valid(&why)) throw ConfigError("program extent: " + why);
  const bool lathe2 = machine.kind == "lathe2";
  double machine_radius = 0.0;  // lathe2: the eye cylinder before the first stop
  double bare_radius = 0.0;     // the mandrel's largest radius
  if (lathe2) {
    const RadiusProfile swept = swept_profile(plan, &mandrel);
    for (double r : swept.radius) bare_radius = std::max(bare_radius, r);
    machine_radius = make_envelope(swept, machine.envelope, "lathe2").r.front();
    // The k-th stop comes before layer k + 1 (0-based): its eye runs outside that layer's surface.
    for (std::size_t k = 0; k < program.eye_stops.size(); ++k) {
      const GcodeEyeStop& s = program.eye_stops[k];
      double surface = bare_radius;
      std::string what = "the mandrel reaches radius ";
      if (k + 1 < plan.layers.size()) {
        surface = plan.layers[k + 1].surface_radius;
        what = "layer " + std::to_string(k + 2) + " (" + plan.layers[k + 1].name +
               ") is wound on a surface reaching radius ";
      } else {
        for (const LayerSummary& l : plan.layers) surface = std::max(surface, l.surface_radius);
        if (!plan.layers.empty()) what = "the outermost layer's surface reaches radius ";
      }
      if (!(s.radius > surface)) {
        throw InputError(name + ":" + std::to_string(s.line) +
                         ": the stop sets the eye at radius " + format_shortest(s.radius) +
                         " mm, inside the part: " + what + format_fixed(surface, 2) +
                         " mm; the eye runs outside it (windplan names that radius + "
                         "machine.envelope.clearance)");
      }
    }
  }
  // The eye's travel as the replay measures it (export/program/replay.cpp): the chord between the
  // eye's positions in the mandrel frame and the arc the spindle turns it through.
  ProgramExtent out;
  const GcodeBlock* prev = nullptr;
  for (const GcodeBlock& b : program.blocks) {
    if (prev && !b.rapid) {
      const double y0 =
          lathe2 ? (prev->eye_radius > 0.0 ? prev->eye_radius : machine_radius) : prev->y;
      const double y1 = lathe2 ? (b.eye_radius > 0.0 ? b.eye_radius : machine_radius) : b.y;
      const double da = (b.a - prev->a) * M_PI / 180.0;
      const double dx = b.x - prev->x;
      const double chord2 = dx * dx + y0 * y0 + y1 * y1 - 2.0 * y0 * y1 * std::cos(da);
      const double chord = std::sqrt(std::max(0.0, chord2));
      out.eye_travel_mm +=
          std::hypot(chord, std::fabs(da) * std::max(std::fabs(y0), std::fabs(y1)));
      if (out.eye_travel_mm > options.max_travel_mm) {
        throw InputError(
            name + ":" + std::to_string(b.line) + ": the eye has travelled more than " +
            format_shortest(options.max_travel_mm / 1e6) +
            " km by this move (the replay's bound: " +
            format_shortest(options.max_travel_mm / 0.5) +
            " sub-steps of 0.5 mm); no winding program moves the eye so far" +
            (program.eye_stops.empty() ? std::string()
                                       : " (is an eye radius named at a stop far too large?)"));
      }
    }
    prev = &b;
  }
  return out;
}

}  // namespace windplan
