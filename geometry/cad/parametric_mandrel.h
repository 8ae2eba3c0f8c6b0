#pragma once
// Parametric mandrels built as closed OpenCASCADE solids (so that they can be exported to STEP):
// a pipe (cylinder), a cone frustum, a pressure vessel (cylinder plus two domes with polar
// openings) and a bent tube (a circular tube swept along straight segments and bends).
//
// Frame: the spindle axis is +Z through the origin for pipe, cone and vessel, whose cylindrical
// (or conical) part runs from z = 0 to z = length; the bent tube starts at the origin heading +Z.
// Planar faces of these solids are exactly their end caps (the pipe/cone ends, the vessel's
// polar-opening disks, the tube ends); every other face is the wound surface.
//
// Isotensoid dome (netting theory, geodesic winding, internal pressure): with fibre angle
// sin(alpha) = r0 / r (Clairaut) and fibre stresses only, membrane equilibrium of a shell of
// revolution gives, for the meridian slope angle psi (against the radial direction),
//   d ln(sin psi) / dr = 2 / r - r0^2 / (r (r^2 - r0^2)),  i.e.  sin psi = k r^3 / sqrt(r^2 - r0^2)
// and with psi = 90 deg at the equator r = R (rho = r / R, rho0 = r0 / R):
//   dz/dr = - rho^3 sqrt(1 - rho0^2) / sqrt((rho^2 - rho0^2) - (1 - rho0^2) rho^6).
// The radicand vanishes at rho = 1 and at a neck radius rho1 slightly above rho0 (vertical
// tangents at both ends); the dome is the meridian between them, so its opening radius is
// r1 = rho1 R (reported by isotensoid_neck_radius), a fraction of a percent above r0.
// Reference: e.g. Peters (ed.), Composite Filament Winding, ASM 2011, ch. 4 (netting analysis).
#include <string>
#include <vector>

#include "geometry/cad/cad_shape.h"
#include "geometry/mesh/mesh.h"

namespace windplan {

struct PipeParams {
  double radius = 50.0;   ///< mm, > 0
  double length = 500.0;  ///< mm, > 0
  bool is_valid(std::string* why) const;
};

struct ConeParams {
  double radius_start = 60.0;  ///< mm at z = 0, > 0
  double radius_end = 40.0;    ///< mm at z = length, > 0
  double length = 400.0;       ///< mm, > 0
  bool is_valid(std::string* why) const;
};

enum class DomeType { Hemispherical, Elliptical, Isotensoid };

struct DomeParams {
  DomeType type = DomeType::Hemispherical;
  /// Elliptical only: dome height / vessel radius (dimensionless, > 0).
  double aspect = 0.6;
  /// Polar-opening (boss) radius (mm), 0 < polar_opening < vessel radius.
  double polar_opening = 30.0;
};

struct VesselParams {
  double radius = 100.0;  ///< cylinder radius (mm), > 0
  double length = 300.0;  ///< cylinder length (mm), >= 0
  DomeParams dome_start;  ///< dome below z = 0
  DomeParams dome_end;    ///< dome above z = length
  /// Points of the isotensoid meridian (the B-spline revolved is interpolated through them).
  int isotensoid_samples = 161;
  bool is_valid(std::string* why) const;
};

struct BendParams {
  double angle = 90.0;       ///< degrees, in (0, 180]
  double radius = 100.0;     ///< centreline bend radius (mm), > tube radius
  double plane_angle = 0.0;  ///< degrees: rotation of the bend plane about the incoming segment
};

struct BentTubeParams {
  double radius = 25.0;                    ///< tube radius (mm), > 0
  std::vector<double> segments{200, 200};  ///< straight lengths (mm, >= 0), at least one
  std::vector<BendParams> bends = std::vector<BendParams>(1);  ///< segments.size() - 1 bends
  bool is_valid(std::string* why) const;
};

/// A closed cylinder of the pipe's radius and length (the wound surface is its side).
CadShape make_pipe(const PipeParams& p);
/// A closed cone frustum.
CadShape make_cone(const ConeParams& p);
/// A closed vessel: domes revolved from their meridians, capped by planar disks at the openings.
CadShape make_vessel(const VesselParams& p);
/// A closed bent tube (circular section swept along the centreline, flat end caps).
/// \throw ConfigError for invalid parameters (each make_* does).
CadShape make_bent_tube(const BentTubeParams& p);

/// A closed sphere centred at the origin (two poles on the z axis: degenerate B-rep edges). A
/// reference shape for tests of the tessellation's pole handling. \throw ConfigError for
/// radius <= 0.
CadShape make_sphere(double radius);

/// The meridian of one dome as (r, h) points from the equator (R, 0) to the opening (r_open,
/// height), h measured from the equator away from the cylinder; `n` >= 2 points.
std::vector<Vec2> dome_meridian(const DomeParams& d, double vessel_radius, int n);
/// The actual opening radius of a dome: polar_opening, or the isotensoid neck r1 (see above).
double dome_opening_radius(const DomeParams& d, double vessel_radius);
/// The isotensoid neck radius r1 (mm) for vessel radius R and polar opening r0.
double isotensoid_neck_radius(double R, double r0);

/// Centreline of a bent tube as a polyline (mm), `per_bend` points per bend; for tests/reports.
std::vector<Vec3> bent_tube_centreline(const BentTubeParams& p, int per_bend = 32);
/// Total centreline length (mm): sum of segments plus bend radius times angle.
double bent_tube_length(const BentTubeParams& p);

const char* to_string(DomeType t);
/// "hemispherical", "elliptical", "isotensoid". \throw InputError otherwise.
DomeType parse_dome_type(const std::string& s);

}  // namespace windplan
