#pragma once
// Parametric mandrels with a non-circular section, and the features of real CAD mandrels, built
// as closed OpenCASCADE solids like geometry/cad/parametric_mandrel.h.
//
// Section mandrels (tanks, booms): an ellipse (semi-axes a along X, b along Y) or a rounded
// rectangle (width along X, height along Y, corner radius) extruded along +Z from z = 0 to
// z = length; the spindle axis is the section's centre line (+Z through the origin). Each end is
// flat (a planar cap) or a dome: the section lofted (BRepOffsetAPI_ThruSections, smooth) through
// copies of itself scaled by cos(u) at heights height * sin(u) / sin(u1), u in [0, u1] with
// cos(u1) = opening / a (or opening / (width / 2)), closed by a planar cap at the opening. The
// dome starts tangent to the wall (scale 1, vertical tangent) and its opening is the section
// shape scaled to `opening`.
//
// Features (MandrelFeatures), applied to any parametric body with OCCT booleans: a through bore
// along the axis, shaft ends for the chuck and tailstock beyond the body's ends, flanges (disks
// about the axis) with bolt holes on a pitch circle, and screw tabs (blocks sticking out of the
// wall with a hole parallel to the axis).
#include <functional>
#include <string>
#include <vector>

#include "geometry/cad/cad_shape.h"
#include "geometry/mesh/mesh.h"

namespace windplan {

enum class SectionShape { Ellipse, RoundedRectangle };

struct SectionEndParams {
  bool dome = false;     ///< false: a flat cap at the end of the extrusion
  double height = 50.0;  ///< dome height along the axis (mm), > 0
  /// Dome opening: the section scaled to this half-width along X (mm), 0 < opening < a (or
  /// width / 2).
  double opening = 20.0;
};

struct SectionParams {
  SectionShape shape = SectionShape::Ellipse;
  double semi_x = 80.0;         ///< ellipse semi-axis along X (mm), > 0
  double semi_y = 50.0;         ///< ellipse semi-axis along Y (mm), > 0
  double width = 160.0;         ///< rounded rectangle: extent along X (mm), > 0
  double height = 100.0;        ///< rounded rectangle: extent along Y (mm), > 0
  double corner_radius = 20.0;  ///< rounded rectangle: corner radius (mm), 0 < r <= min(w, h) / 2
  double length = 400.0;        ///< extrusion length (mm), > 0
  SectionEndParams end_start;   ///< the end at z = 0
  SectionEndParams end_end;     ///< the end at z = length
  bool is_valid(std::string* why) const;
  /// An elliptical section a x b (semi-axes along X and Y, mm), `length` long, flat ends.
  static SectionParams ellipse(double a, double b, double length);
  /// A rounded-rectangle section (mm), `length` long, flat ends.
  static SectionParams rounded_rectangle(double width, double height, double corner_radius,
                                         double length);
  /// Half-width of the section along X (mm): semi_x or width / 2.
  double half_x() const { return shape == SectionShape::Ellipse ? semi_x : 0.5 * width; }
};

/// Perimeter of the section (mm): Ramanujan's second formula for the ellipse (relative error
/// below 3 h^5 / 2^17, h = ((a - b) / (a + b))^2), 2 (w + h) - (8 - 2 pi) r for the rounded
/// rectangle.
double section_perimeter(const SectionParams& p);
/// Distance from the axis to the section outline in the direction at angle `theta` (radians,
/// from +X towards +Y), mm.
double section_radius(const SectionParams& p, double theta);

/// A closed section mandrel. \throw ConfigError for invalid parameters.
CadShape make_section_mandrel(const SectionParams& p);

struct ShaftParams {
  double radius = 0.0;  ///< mm; 0 = no shaft
  double length = 0.0;  ///< mm beyond the body's end, > 0 when radius > 0
};

struct FlangeParams {
  double at = 0.0;             ///< axial position of the flange's lower face (mm)
  double radius = 80.0;        ///< outer radius (mm), larger than the body there
  double thickness = 10.0;     ///< along the axis (mm), > 0
  int bolts = 0;               ///< bolt holes on the pitch circle (count, >= 0)
  double bolt_radius = 4.0;    ///< mm, > 0 when bolts > 0
  double pitch_radius = 70.0;  ///< mm; the holes must lie inside the flange
};

struct TabParams {
  double at = 0.0;           ///< axial position of the tab's lower face (mm)
  int count = 2;             ///< tabs spread evenly around the axis, the first at `angle`
  double angle = 0.0;        ///< degrees from +X towards +Y
  double reach = 25.0;       ///< how far the tab sticks out of the wall (mm), > 0
  double width = 20.0;       ///< tangential width (mm), > 0
  double thickness = 8.0;    ///< along the axis (mm), > 0
  double hole_radius = 3.0;  ///< screw hole parallel to the axis (mm), 0 = none, < width / 2
};

struct MandrelFeatures {
  double bore = 0.0;        ///< radius of a through bore along the axis (mm); 0 = none
  ShaftParams shaft_start;  ///< below the body's lowest point
  ShaftParams shaft_end;    ///< above the body's highest point
  std::vector<FlangeParams> flanges;
  std::vector<TabParams> tabs;
  bool empty() const;
  /// Checks the values on their own (signs, holes inside their flange or tab); `key` prefixes
  /// the names in the message ("features").
  bool is_valid(std::string* why, const std::string& key = "features") const;
};

/// The body with its features: the bore cut through, shafts and flanges fused on (the shafts at
/// the body's axial extent), bolt holes cut through the flanges, tabs fused on at the outline
/// (`outline(theta)` gives the wall's distance from the axis, mm) with their holes cut.
/// \throw ConfigError for invalid features (naming `features.<key>`), InvariantError when a
/// boolean fails.
CadShape add_mandrel_features(const CadShape& body, const MandrelFeatures& f,
                              const std::function<double(double)>& outline);

const char* to_string(SectionShape s);

}  // namespace windplan
