#pragma once
// The surface the payout eye moves on, per machine kind (issue #13):
//   - lathe2: a cylinder about the spindle axis (the machine has no cross-feed), of radius
//     envelope.radius, or the mandrel's largest radius + clearance when that is 0;
//   - lathe4 and robot: the clearance envelope, the set of points at distance `clearance` from
//     the swept mandrel. The mandrel turns under the eye, so what the eye must clear is the solid
//     swept by the mandrel about the spindle, whose meridian is the region under the radius
//     profile R(x) (the largest radius at each station, geometry/region/axis.h). The envelope
//     radius R_env(x) is the top of that region dilated by a disc of radius `clearance` (the
//     Minkowski sum): for each profile segment the top of its capsule (two end discs and the
//     segment moved by `clearance` along its upward normal), maximised over segments. The profile
//     is extended as a constant beyond its ends (the shaft or boss carrying the mandrel there).
//     R_env is sampled at every profile station, every station +/- clearance and at steps of at
//     most min(1 mm, clearance / 10), so its chords fall at most h^2 / (8 clearance) <= 0.006 mm
//     (clearance 20) inside the exact dilation;
//     a robot uses it only without a mandrel mesh: with one, its eye is at the true clearance
//     from the unswept mandrel (export/machine/clearance_eye.h);
//   - profile mode: the explicit (x, r) polyline (lathe4, robot; lathe2 only if it is constant);
//   - free_length mode: no envelope (lathe4, robot).
// A point at (x, R_env(x)) of a surface of revolution is at distance >= clearance from the mandrel
// (the closest point of a surface of revolution lies in the point's meridian half-plane), and the
// eye is checked against the mandrel mesh anyway (export/machine/clearance.h).
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "planner/job/machine_options.h"
#include "planner/plan/plan.h"

namespace windplan {

/// The eye envelope R_env(x) (or the fixed free-length mode).
struct Envelope {
  bool fixed_length = false;
  double free_length = 0.0;  ///< mm, fixed_length mode
  std::vector<double> x;     ///< mm, strictly increasing
  std::vector<double> r;     ///< mm
  double max_slope = 0.0;    ///< max |dr/dx|
  /// "cylinder r = 120 mm", "clearance envelope (20 mm from the swept mandrel)", ...
  std::string description;
  double radius_at(double ax) const;
};

/// Builds the envelope of machine `kind` ("lathe2", "lathe4", "robot") from the envelope options
/// and the mandrel's radius profile.
/// \throw InputError when the mode needs a mandrel profile and the plan has none; ConfigError
///        for lathe2 with a non-constant profile or a free length (no cross-feed to follow it).
Envelope make_envelope(const RadiusProfile& mandrel, const EnvelopeOptions& opts,
                       const std::string& kind = "lathe4");

/// The swept mandrel's radius profile for the envelope: with a mesh, its largest radius about the
/// plan's axis at stations at most 0.5 mm apart (at least 200, at most 4000:
/// geometry/region/winding_surface.h), so that a bend bulging between the plan's 200 stations is
/// not missed (0.31 mm inside the clearance on the shipped bent tube with the plan's profile);
/// without one, the plan's profile.
RadiusProfile swept_profile(const WindingPlan& plan, const Mesh* mandrel);

/// The dilation of the region under `profile` by a disc of radius `clearance` (see the header
/// comment), as (x, r) samples spanning [x0 - clearance, xn + clearance].
RadiusProfile dilate_profile(const RadiusProfile& profile, double clearance);

}  // namespace windplan
