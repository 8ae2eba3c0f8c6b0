#pragma once
// A structural model of the wound part that CalculiX (`ccx`) runs as written: an Abaqus-format
// input deck (model.inp) of layered shells on the mandrel surface under internal pressure.
//
// Elements. Each triangle of the mesh whose laminate is at least min_thickness thick becomes a
// six-node shell S6 (CalculiX takes *SHELL SECTION, COMPOSITE only on S6 and S8R): its corners
// and the midpoints of its edges (on a shape of revolution each midpoint is put back on the
// surface: its distance from the axis is the mean of the two corners'). The element is oriented
// with its normal away from the axis. Triangles without laminate (inside the turnarounds, at the
// polar openings) are left out: the bosses there are not modelled, their pressure load is.
//
// Laminate. Per element, innermost first, each layer of the laminate gives its +alpha and -alpha
// plies (each half the layer's thickness at the element), at the angles measured from the laid
// paths in that face (export/files/laminate_fea.h); a family no path crossed takes the other
// family's angle mirrored, and when neither crossed it, a helical layer takes the geodesic angle
// asin(c / r) at the face (c its Clairaut constant), a hoop layer its measured angle. Each ply has
// its own *ORIENTATION: local 1 along the fibre f = cos(a) m + sin(a) h (m the face's meridian
// direction, h = m x n), local 2 = n x f in the face. One orthotropic material (engineering
// constants of the ply, planner/layup/laminate_theory.h). The shell's reference surface is its
// mid-surface on the mandrel surface (no offset).
//
// Loads and supports. Internal pressure p on every element (*DLOAD P, positive along the
// element normal, i.e. outward, as CalculiX applies it to shells). Each open end of the model
// (its boundary edges on the start side and on the end side of the middle of its axial extent)
// carries the axial end load of a closed vessel: p times the area its boundary encloses about
// the axis, spread uniformly along the boundary (consistent loads of a quadratic edge: 1/6,
// 4/6, 1/6), outward along the axis. The loads are self-equilibrated; three corner nodes on the
// middle parallel (at 0, 90 and 180 deg about the axis) take the six rigid-body motions (3-2-1:
// all three components, then two, then one, along the axis frame: *BOUNDARY for a global
// direction, else *EQUATION), so the supports carry no load.
//
// Output requested: nodal displacements and, per element and integration point, stresses and
// strains in each ply's local system (*NODE PRINT U, *EL PRINT S, E into model.dat). The plies
// of each element go to model_plies.csv (element, ply, layer index, layer name, angle [deg],
// thickness [mm]) for `windplan check-fea` (export/files/ccx_results.h). Units: mm, N, MPa.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "export/files/csv.h"
#include "export/files/laminate_fea.h"
#include "planner/layup/laminate_theory.h"

namespace windplan {

struct FeaModelOptions {
  /// Internal pressure (MPa, > 0).
  double pressure = 1.0;
  /// Faces with less laminate than this are left out (mm, > 0).
  double min_thickness = 0.01;
  /// The mesh is a surface of revolution about the axis (midside nodes put back on it).
  bool revolution = true;
  bool is_valid(std::string* why) const;
};

/// Per layer, what a face no path crossed takes (header comment).
struct FeaLayerFallback {
  double clairaut = 0.0;  ///< helical: c (mm); 0 for a hoop layer
  double angle = 0.0;     ///< hoop: its measured angle (deg)
};

struct FeaPly {
  int layer = 0;           ///< index of the wound layer (innermost 0)
  double angle_deg = 0.0;  ///< from the meridian
  double thickness = 0.0;  ///< mm
  Vec3 fibre = Vec3::Zero();
  Vec3 across = Vec3::Zero();  ///< n x fibre
};

struct FeaModel {
  std::vector<Vec3> nodes;                   ///< corners, then midside nodes
  std::vector<std::array<int, 6>> elements;  ///< 0-based node indices (S6 order)
  std::vector<int> element_face;             ///< the mesh face of each element
  std::vector<std::vector<FeaPly>> plies;    ///< per element, innermost first
  std::vector<std::string> layer_names;
  struct Load {
    int node;
    Vec3 force;  ///< N
  };
  std::vector<Load> end_loads;
  struct Support {
    int node;
    Vec3 direction;  ///< unit
  };
  std::vector<Support> supports;
  double pressure = 0.0;
  int faces_left_out = 0;
  double end_force[2] = {0.0, 0.0};  ///< N, start and end side
};

/// Builds the model of `layers` on `mesh` (header comment).
/// \throw InputError when arrays do not match the mesh, or no face has laminate;
///        ConfigError for invalid options.
FeaModel build_fea_model(const Mesh& mesh, const SpindleAxis& axis,
                         const std::vector<LaminateLayerFaces>& layers,
                         const std::vector<FeaLayerFallback>& fallback,
                         const FeaModelOptions& options);

/// The CalculiX / Abaqus input deck of `model` with the ply's constants.
std::string calculix_deck(const FeaModel& model, const ElasticConstants& ply,
                          const std::string& heading);

/// model_plies.csv (header comment).
CsvTable fea_plies_table(const FeaModel& model);

/// Writes model.inp and model_plies.csv into dir; returns their names. \throw IoError
std::vector<std::string> write_fea_model(const std::filesystem::path& dir, const FeaModel& model,
                                         const ElasticConstants& ply, const std::string& heading);

}  // namespace windplan
