#pragma once
// Sections of a triangle mesh by planes: the chains of edge crossings, and which closed chain
// goes around the mandrel. Cut-lines (planner/cutlines) refine from them, coverage and the
// helix planner (planner/winding) measure and start on them.
//
// Units: mm. Frames: the mesh frame.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"
#include "geometry/region/axis.h"

namespace windplan {

/// A section of a mesh by a plane: one chain of edge crossings.
struct PlaneSection {
  SurfacePath path;          ///< closed: a cyclic face strip; open: crossings only (see below)
  std::vector<Vec3> points;  ///< the crossing points in chain order
  bool closed = true;        ///< false when the chain runs into the mesh boundary
  double length = 0.0;       ///< mm (closed: including the closing segment)
  int winding = 0;           ///< turns around the axis (closed chains; 0 when it does not wind)
  /// A closed loop around the mandrel: on an annulus, it separates the two boundary loops (it
  /// is not contractible); on other meshes, it winds around the axis.
  bool around = false;
};

/// All chains of the section of `mesh` by {p : n . p = d} (n normalised here). A vertex exactly
/// on the plane counts as lying on its positive side (symbolic perturbation), so the chains are
/// well defined. For open chains only `points`, `length` and `closed` are meaningful.
std::vector<PlaneSection> plane_sections(const Mesh& mesh, const Vec3& normal, double offset,
                                         const SpindleAxis& axis);

/// The section loop around the mandrel (PlaneSection::around; the longest if several are).
/// \throw InputError naming `what` when the plane misses the mesh or no closed section loop
///        winds around the axis.
PlaneSection axial_plane_section(const Mesh& mesh, const Vec3& normal, double offset,
                                 const SpindleAxis& axis, const std::string& what);

/// The shorter piece, between a and b, of the section chain of the plane {n . p = offset} that
/// passes through both points (within `tolerance` mm), as the polyline a, crossings..., b; empty
/// when no chain passes through both.
std::vector<Vec3> section_arc(const Mesh& mesh, const Vec3& normal, double offset, const Vec3& a,
                              const Vec3& b, double tolerance);

/// Plane sections of one mesh, with the state that tells whether a closed section loop goes
/// around the mandrel precomputed once (precompute / query split: many planes, one mesh).
class PlaneSectioner {
 public:
  /// Precomputes, on an annulus, an edge path between its two boundary loops.
  PlaneSectioner(const Mesh& mesh, const SpindleAxis& axis);

  /// All chains of the section by {p : n . p = offset} (n normalised here); see plane_sections.
  std::vector<PlaneSection> sections(const Vec3& normal, double offset) const;

  /// The loop around the mandrel: the longest (near == nullptr) or the one whose centroid is
  /// nearest to *near. Returns false when there is none; `all` receives every chain.
  bool around_loop(const Vec3& n, double d, const Vec3* near, PlaneSection* out,
                   std::vector<PlaneSection>* all = nullptr) const;

  /// The mean of the points (zero for none).
  static Vec3 centroid(const std::vector<Vec3>& pts);

 private:
  const Mesh& mesh_;
  SpindleAxis axis_;
  std::vector<char> transversal_;  ///< per edge: on the path between the two boundary loops
};

/// The shorter piece of a section chain of `sections` between two points lying on it (within
/// `tolerance` mm), as the polyline a, crossings..., b. Empty when no chain passes through both.
std::vector<Vec3> arc_between(const std::vector<PlaneSection>& sections, const Vec3& a,
                              const Vec3& b, double tolerance);

/// Length of a polyline (mm), closed: with the segment from the last point to the first.
double polyline_length(const std::vector<Vec3>& pts, bool closed);

}  // namespace windplan
