#pragma once
// The wound region of a real mandrel: an axial range along the spindle axis and the surface in it
// that goes around the axis (shaft ends, flanges, bolt holes, tabs and inner bores left out).
//
// select_region() cuts the full mesh exactly on the two station planes
// (geometry/region/plane_cut.h), splits the faces between them into connected candidate regions and
// picks one: the outer surface around the axis (default), the inner one, or a candidate by index. A
// candidate "goes around the axis" when one of its boundary loops has winding number +-1 about the
// axis (loops projected onto the plane normal to it). The chosen candidate must be an annulus: one
// component, genus 0, exactly two loops, both around the axis.
//
// candidate_regions() describes the components of any face selection (the table printed by
// `windplan mandrel` and listed in the error for a non-annulus), and suggest_region() proposes
// the axial range of the longest stretch of mandrel whose section keeps the same topology and
// outline: it cuts the mesh by many station planes, counts on rays from the axis how many sheets
// the section crosses and how far out the outermost one is, and takes the longest run of
// stations where neither changes by more than a tolerance (a flange, a tab or a shaft shoulder
// changes both), carries it on while the sheets stay the same and no flat face across the axis
// is met (so that it follows a dome to its opening), then checks the range with select_region().
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "geometry/region/plane_cut.h"

namespace windplan {

/// `mandrel.region`: which part of the mandrel is wound.
struct RegionOptions {
  bool enabled = false;           ///< a region was given
  double start = 0.0;             ///< mm, axial station of the start plane along the axis
  double end = 0.0;               ///< mm, axial station of the end plane, > start
  std::string surface = "outer";  ///< "outer" or "inner": the surface around the axis to take
  int component = 0;              ///< 1-based candidate index (overrides surface); 0 = by surface
  PlaneCutOptions cut;            ///< the exact plane cut (no-sliver fraction)
  /// `region.centre_line`: the ends are sections normal to the tube's centre line at two
  /// stations (geometry/region/centre_line_region.h) instead of planes normal to the axis;
  /// start/end are then unused.
  bool centre_line = false;
  double from = 0.0;           ///< mm of arc length along the centre line (centre_line.from)
  double to = 0.0;             ///< mm (centre_line.to), > from
  bool from_fraction = false;  ///< `from` is a fraction of the centre line's length ([0, 1])
  bool to_fraction = false;    ///< `to` is a fraction of the centre line's length ([0, 1])
  bool is_valid(std::string* why) const;
};

/// One connected part of a face selection.
struct CandidateRegion {
  int index = 0;               ///< 1-based, in the order of the table
  int faces = 0;               ///< triangles
  double area = 0.0;           ///< mm^2
  double axial_min = 0.0;      ///< mm, along the axis
  double axial_max = 0.0;      ///< mm
  double radius_min = 0.0;     ///< mm, distance of its vertices from the axis
  double radius_max = 0.0;     ///< mm
  double mean_radius = 0.0;    ///< mm, area-weighted radius of the face centroids
  int loops = 0;               ///< boundary loops (-1: not a manifold patch)
  int loops_around = 0;        ///< boundary loops with winding number +-1 about the axis
  int genus = 0;               ///< from V - E + F = 2 - 2 genus - loops
  bool around = false;         ///< goes around the axis (loops_around > 0)
  bool annulus = false;        ///< genus 0, two loops, both around the axis
  std::vector<int> face_list;  ///< its faces in the mesh the selection was made on
  /// "#2: axial 10..490 mm, radius 50..50 mm, 2 loops (2 around the axis), genus 0, 3200 mm^2"
  std::string brief() const;
};

/// The connected parts (through shared edges) of the faces f with select[f] != 0, largest area
/// first. \throw InputError when select has the wrong size.
std::vector<CandidateRegion> candidate_regions(const Mesh& mesh, const std::vector<char>& select,
                                               const SpindleAxis& axis);

/// A table of candidates, one per line, each line indented by `indent`.
std::string region_table(const std::vector<CandidateRegion>& regions,
                         const std::string& indent = "  ");

struct RegionSelection {
  Mesh mesh;                                ///< the full mesh cut on the two planes
  std::vector<int> face_parent;             ///< per face of `mesh`: the input mesh's face
  std::vector<char> keep;                   ///< per face of `mesh`: in the chosen candidate
  std::vector<CandidateRegion> candidates;  ///< all faces between the planes, by component
  int chosen = -1;                          ///< index into candidates
  int split_edges = 0, split_faces = 0, moved_vertices = 0;  ///< plane-cut figures
  double max_move = 0.0;                                     ///< mm
};

/// Cuts `full` on the region's planes and picks the candidate.
/// \throw ConfigError naming the mandrel.region key for: a range that misses the mandrel, a range
///        where no surface goes around the axis, several surfaces around the axis that do not
///        nest (choose mandrel.region.component), a component index out of range, a chosen
///        surface that is not an annulus (with the candidates and a suggested range).
RegionSelection select_region(const Mesh& full, const SpindleAxis& axis,
                              const RegionOptions& options);

struct RegionSuggestion {
  bool found = false;
  double start = 0.0, end = 0.0;  ///< mm, a range whose outer surface is an annulus
  double radius = 0.0;            ///< mm, mean radius of that outer surface
  /// "region: {start: 12.5, end: 487.5}" (the YAML to put under mandrel:), or "" if none.
  std::string keys() const;
};

/// A range of the full mandrel whose outer surface is a clean annulus (see the file comment).
/// \param stations number of station planes over the mesh's axial extent (>= 8)
RegionSuggestion suggest_region(const Mesh& full, const SpindleAxis& axis, int stations = 240);

}  // namespace windplan
