#pragma once
// The thickness of a wound layer along the meridian of a shape of revolution, from fibre
// continuity, and the outer surface it leaves (the meridian offset by that thickness) for the
// next layer.
//
// Fibre continuity. A helical layer of K circuits (2K passes: out and return) of bands B wide and
// t thick crosses every parallel of radius r 2K times; each band covers B / cos(a) of the
// parallel's 2 pi r, a the winding angle from the meridian, so the layer is
//   t_h(r) = 2 K B t / (2 pi r cos a(r))                                          (1)
// thick there. On a geodesic (Clairaut, r sin a = c) r cos a = sqrt(r^2 - c^2): on a cylinder of
// radius R, 2 K B t / (2 pi R cos a_R), which is 2 t at full coverage (K = 2 pi R cos a_R / B),
// and on a dome t(r) / t(R) = R cos a_R / (r cos a_r). (1) diverges at the turnaround r = c; the
// band is B wide, so a point of the meridian is covered by the bands whose centre lines pass
// within B / 2 of it: the laminate is (1) averaged over a band width of meridian arc length,
//   t(s) = (1 / B) integral from s - B/2 to s + B/2 of t_h(s') ds',                (2)
// t_h = 0 where r < c (no fibre inside the turnaround). The singularity is integrable: with r
// linear in s on a segment of slope m = dr/ds, integral ds / sqrt(r^2 - c^2) =
// [ln(r + sqrt(r^2 - c^2))] / m, evaluated exactly per segment of the polyline (the window is
// clipped to the meridian; (2) conserves integral t ds). This is the band-width correction of
// the winding literature (e.g. Vasiliev & Morozov, Advanced Mechanics of Composite Materials,
// 2007, ch. 7; Wang et al., Composite Structures 2011, the "t(r) averaged over a band" model).
//
// A hoop layer over the axial range [x0, x1] with axial pitch p: each of its passes crosses a
// meridian line once per turn, the band covering B / sin(a) of the meridian, and advances p_s =
// p / cos(psi) of meridian per turn (psi the meridian's slope against the axis), so it is
//   t_p(s) = passes B t / (p_s sin a),  tan a = 2 pi r / p_s                       (3)
// thick on the range (the reversal triangles beyond the pitch are left out) and 0 elsewhere.
//
// Offset. The next layer is wound on the meridian moved along its outward normal (in the
// (axial, radius) half-plane, (-dr/ds, dx/ds) for a meridian run with increasing s) by t(s).
// The offset is rejected when it would close a polar opening: when an end of the meridian would
// reach the axis (r <= 0), or when the offset curve folds back on itself near an end (a
// thickness above the radius of curvature of a concave meridian: a segment of the offset runs
// against its original).
// Units: mm.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"

namespace windplan {

/// A meridian of a shape of revolution as a polyline in the (axial, radius) half-plane, in order
/// from the start end to the other end, with its arc length.
struct MeridianPolyline {
  std::vector<Vec2> points;  ///< (axial mm, radius mm), at least two, consecutive points distinct
  std::vector<double> s;     ///< arc length at each point (mm), s[0] = 0

  /// From points; \throw InputError for fewer than two points, a radius < 0 or two equal
  /// consecutive points.
  static MeridianPolyline from_points(std::vector<Vec2> points);
  /// From a radius profile (axial increasing).
  static MeridianPolyline from_profile(const RadiusProfile& profile);
  /// The same curve with points at most `step` mm apart (the original points are kept).
  MeridianPolyline resampled(double step) const;
  double length() const { return s.empty() ? 0.0 : s.back(); }
  /// The point at arc length s (clamped).
  Vec2 at(double s) const;
  /// Unit outward normal (-dr/ds, dx/ds) at point i (average of its segments' normals).
  Vec2 normal(int i) const;
  /// Arc length of the point of the polyline nearest to q.
  double project(const Vec2& q) const;
  /// As a radius profile (axial must be strictly increasing; \throw InputError otherwise).
  RadiusProfile to_profile() const;
};

/// A layer's thickness at the points of a meridian.
struct LayerThickness {
  std::vector<double> s;          ///< arc length (mm), the meridian's points
  std::vector<double> thickness;  ///< mm
  /// Linear interpolation at arc length s (0 outside).
  double at(double s) const;
  double max() const;
};

/// A laminate on a shape of revolution: the mandrel's meridian and, per layer, its thickness and
/// the outer surface after it (each surface has the points of the one under it, offset one for
/// one, so point i of every surface comes from point i of the mandrel's meridian).
struct LaminateProfiles {
  MeridianPolyline mandrel;                ///< the mandrel's meridian
  std::vector<std::string> names;          ///< per layer, innermost first
  std::vector<LayerThickness> thickness;   ///< per layer, at the points of the surface under it
  std::vector<MeridianPolyline> surfaces;  ///< per layer: the outer surface after it
  /// With design.dome_thickness: spline, per layer the other model's thickness (helical: fibre
  /// continuity averaged over a band; hoop: the same as `thickness`) for the profiles to show
  /// both; empty otherwise.
  std::vector<LayerThickness> alternative;
  std::string alternative_name;  ///< e.g. "continuity"
};

/// Equation (1) at radius r: 2 K B t / (2 pi sqrt(r^2 - c^2)); 0 for r <= c.
double helical_thickness_unbounded(double r, double c, double circuits, double band_width,
                                   double band_thickness);

/// Equation (2) at every point of `meridian`: a geodesic helical layer with Clairaut constant c
/// (mm, >= 0, below the largest radius), `circuits` K (> 0), bands band_width B wide and
/// band_thickness t thick.
/// \throw InputError for invalid figures, or when the meridian runs along r = c over a segment
///        (a hoop: (1) is not integrable there).
LayerThickness helical_layer_thickness(const MeridianPolyline& meridian, double c, double circuits,
                                       double band_width, double band_thickness);

/// Equation (3) at every point of `meridian` for a hoop layer over axial positions [x0, x1].
LayerThickness hoop_layer_thickness(const MeridianPolyline& meridian, double x0, double x1,
                                    double pitch, double band_width, double band_thickness,
                                    int passes);

/// The meridian moved along its outward normal by `thickness` (interpolated at its points).
/// \param what names the layer in messages (e.g. "layers[2]")
/// \throw InputError "<what>: ... would close the polar opening ..." (header comment).
MeridianPolyline offset_meridian(const MeridianPolyline& meridian, const LayerThickness& thickness,
                                 const std::string& what);

}  // namespace windplan
