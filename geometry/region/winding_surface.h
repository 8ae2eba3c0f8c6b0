#pragma once
// The wound region of a mandrel and its spindle axis.
//
// The planner works on an annulus: for a vessel the surface between the two polar openings, for
// a pipe or bent tube its side between the two ends. extract_winding_surface() cuts it out of the
// full welded mesh (a face selection, e.g. "every face that is not a planar end cap") as a Mesh
// of its own, with the maps back to the full mesh and its two boundary loops, start loop first
// (the one at the lower axial position).
//
// infer_spindle_axis() finds the axis of a mesh: the principal axes of the area-weighted surface
// second moment (covariance of the surface about its centroid, exact per triangle); a surface of
// revolution has two equal moments and the distinct one is its axis. Revolution is then verified
// by cutting the mesh with planes normal to the axis: in every angular sector of a plane, the
// smallest and largest distance of the edge crossings from the axis must be the same (up to the
// tessellation's sagitta); a shape that fails keeps the principal axis of largest extent and says
// so.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"

namespace windplan {

/// One boundary loop of the winding surface.
struct WindingLoop {
  std::vector<int> vertices;  ///< winding-surface vertex indices, in boundary (next()) order
  double length = 0.0;        ///< mm, closed polygon length
  double mean_radius = 0.0;   ///< mm, mean distance of its vertices from the axis
  double axial = 0.0;         ///< mm, mean axial position of its vertices
};

struct WindingSurface {
  Mesh mesh;                         ///< the annulus (vertices renumbered compactly)
  std::vector<int> face_map;         ///< per annulus face: the full mesh's face
  std::vector<int> vertex_map;       ///< per annulus vertex: the full mesh's vertex
  std::array<WindingLoop, 2> loops;  ///< start loop (lower axial position) first
  double area = 0.0;                 ///< mm^2
};

/// Cuts the faces f with keep[f] != 0 out of `full` and checks they form an annulus.
/// \param keep one flag per face of `full`
/// \throw TopologyError when the selection is not one component with two boundary loops and
///        genus 0, saying how many loops and components it has; InputError when keep has the
///        wrong size.
WindingSurface extract_winding_surface(const Mesh& full, const std::vector<char>& keep,
                                       const SpindleAxis& axis);

struct AxisInferenceOptions {
  int slices = 24;                     ///< cutting planes for the revolution check (count, >= 2)
  int sectors = 8;                     ///< angular sectors compared per plane (count, >= 3)
  double revolution_tolerance = 0.02;  ///< max radius spread / max radius (dimensionless, > 0)
  bool is_valid(std::string* why) const;
};

struct AxisInference {
  SpindleAxis axis;             ///< origin at the area centroid; largest component of direction > 0
  bool revolution = false;      ///< the mesh passed the revolution check about `axis`
  double radius_spread = 0.0;   ///< worst spread of sector radii / max radius over planes
  Vec3 moments = Vec3::Zero();  ///< surface second moments (mm^4), ascending
  std::string method;  ///< "revolution axis" or "principal axis (not a surface of revolution)"
};

/// \throw InputError for a mesh without faces; ConfigError for invalid options.
AxisInference infer_spindle_axis(const Mesh& mesh, const AxisInferenceOptions& options = {});

/// Relative radius spread of `mesh` about `axis` (see AxisInference::radius_spread).
double radius_spread(const Mesh& mesh, const SpindleAxis& axis,
                     const AxisInferenceOptions& options = {});

/// The largest radius of the mesh at `stations` + 1 equally spaced axial stations spanning the
/// mesh (vertices and edge crossings of each station plane). \param stations >= 1
/// \param bound_between false: each station holds the vertices nearest to it and the edges
///        crossing its plane, so the profile can dip below the mesh between stations (by 0.07 mm
///        on a bent tube: an eye on the envelope then fell inside the clearance); true: each
///        station holds the largest radius over the two intervals beside it (vertices in them and
///        edge crossings of their planes; along an edge the radius is convex, so that is the
///        largest over each interval), so the linear interpolation is never below the mesh.
RadiusProfile compute_radius_profile(const Mesh& mesh, const SpindleAxis& axis, int stations = 200,
                                     bool bound_between = false);

}  // namespace windplan
