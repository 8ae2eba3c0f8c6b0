#pragma once
// Tube coordinates: the centre line (spine) of a wound region that is a tube, and its sections
// normal to the centre line.
//
// Convention. A spine is a polyline c(s) of the tube's section centres, s the arc length (mm)
// from the centre of the wound region's start loop (loop 0) to the centre of its end loop
// (loop 1), with a unit tangent t(s) pointing from the start to the end. The station s of the tube
// is the section of the wound surface by the plane {p : t(s) . (p - c(s)) = 0} normal to the
// centre line there: the loop of that plane's section that goes around the tube nearest to c(s)
// (geometry/region/plane_section.h, PlaneSectioner::around_loop). A point q of the surface
// belongs to the station s(q) = Spine::project(q): the arc length of the spine point nearest q.
// Winding angles off a shape of revolution are measured to t(s) (alpha = 0 along the tube, 90 deg
// around it), which is what coverage (planner/winding/coverage.h) and the friction paths use.
//
// Two sources:
// - analytic (spine_from_polyline): a parametric bent tube's centre line
//   (geometry/cad/parametric_mandrel.h, bent_tube_centreline) sampled finely;
// - extracted (extract_spine): from the centroids of the sections of a mesh, marching from the
//   start loop's centroid: predict c + h t, cut there normal to t, take the section loop's
//   centroid (its length-weighted mean, not the vertex mean, so that uneven tessellation does not
//   pull it), re-aim t along the chord from the last centre and cut again (`iterations` times);
//   the end loop's centroid closes it. On a torus the chord direction lags the tangent by
//   h / (2 R), so the default step (a quarter of the mean section radius) keeps the sections
//   within 0.6 deg of normal on a bend of 3 tube radii.
// Units: mm. Frame: the mesh frame.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"

namespace windplan {

/// A centre line: points, unit tangents and arc lengths (see the convention above).
struct Spine {
  std::vector<Vec3> points;    ///< c_i (mm), start to end; at least 2
  std::vector<Vec3> tangents;  ///< t_i, unit (central differences of the points)
  std::vector<double> s;       ///< arc length at c_i (mm); s[0] = 0

  double length() const { return s.empty() ? 0.0 : s.back(); }
  bool empty() const { return points.size() < 2; }
  /// The centre point at arc length `at` (clamped to [0, length()]), linear between points.
  Vec3 point(double at) const;
  /// The unit tangent at arc length `at` (clamped), interpolated between points and normalised.
  Vec3 tangent(double at) const;
  /// The arc length of the spine point nearest q; *distance (if given) receives |q - c|.
  double project(const Vec3& q, double* distance = nullptr) const;
};

/// A spine through the given centre-line points (at least 2, no two consecutive equal).
/// \throw InputError otherwise.
Spine spine_from_polyline(const std::vector<Vec3>& points);

struct SpineOptions {
  /// Distance between sections (mm, > 0; NaN: a quarter of the mean radius of the two end loops).
  double step = std::nan("");
  int iterations = 2;       ///< re-aimed cuts per section (count, >= 1)
  int max_sections = 5000;  ///< give up beyond this many (count, >= 2)
  bool is_valid(std::string* why) const;
};

struct SpineSummary {
  int sections = 0;          ///< sections cut
  double step = 0.0;         ///< mm used
  double mean_radius = 0.0;  ///< mean distance of the end loops' points from their centroids (mm)
  /// The largest angle between the plane of a cut and the final normal at its centre (deg): how
  /// far from normal the last cut was.
  double max_tilt_deg = 0.0;
  std::string brief_report() const;
};

struct SpineResult {
  Spine spine;
  SpineSummary summary;
};

/// The centre line of a tube-shaped annulus from its section centroids (see above).
/// \param loops the annulus' two boundary loops (vertex indices; start loop first)
/// \param axis only to tell which section loop goes around the tube
/// \throw InputError naming `what` when a section normal to the centre line does not go around
///        the tube (the region is not a tube, or bends tighter than the step can follow), and
///        ConfigError for invalid options.
SpineResult extract_spine(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops,
                          const SpindleAxis& axis, const SpineOptions& options = {},
                          const std::string& what = "tube centre line");

/// The length-weighted centroid of a closed polyline (the mean of its segments' midpoints weighted
/// by their lengths; the vertex mean for a zero-length loop).
Vec3 loop_centroid(const std::vector<Vec3>& loop);

}  // namespace windplan
