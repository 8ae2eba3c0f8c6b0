#pragma once
// Reading back what CalculiX computed on the structural model (export/files/fea_deck.h) and the
// first-ply failure check of the wound laminate.
//
// model.dat (ccx's printed output): blocks headed " displacements (vx,vy,vz) for set ..." (node,
// u_x, u_y, u_z), " stresses (elem, integ.pnt.,sxx,...)" and " strains (elem, integ.pnt.,exx,
// ...)" (element, integration point, six components, the ply's orientation name). CalculiX
// expands a composite S6 shell into one 3-D element whose integration points run ply by ply
// (the same number per ply, innermost first), and prints an element with an orientation in that
// orientation's system: per ply, 1 along its fibre, 2 across it in the shell, 3 through the
// thickness; the shear strains it prints are tensor components (gamma_12 = 2 e_12).
//
// Check. Per element and ply, the mean over the ply's integration points of eps_1, eps_2,
// gamma_12 and sigma_1. The first-ply failure factor is the maximum-strain criterion:
//   F = max(|eps_1| / eps_1u, |eps_2| / eps_2u, |gamma_12| / gamma_u),
// eps_1u = X / E1 with X = fibre strength x V_f (the ply's fibre-direction strength, as netting
// uses it), eps_2u = Y / E2 (Y the transverse strength), gamma_u = S / G12 (S the shear
// strength); compression is taken with the tensile allowables (conservative for the fibres'
// and the resin's compression). F >= 1: the ply fails at the modelled pressure; for a linear
// model the first ply fails at pressure / F. The fibre factor is |eps_1| / eps_1u alone.
#include <array>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "export/files/csv.h"
#include "geometry/mesh/mesh.h"
#include "planner/layup/laminate_theory.h"

namespace windplan {

struct CcxResults {
  std::map<int, Vec3> displacement;  ///< node (1-based) -> u (mm)
  struct IpValues {
    int element = 0;
    int ip = 0;
    std::array<double, 6> v{};  ///< xx, yy, zz, xy, xz, yz
  };
  std::vector<IpValues> stress;  ///< MPa
  std::vector<IpValues> strain;  ///< tensor components
};

/// Parses model.dat. \throw IoError when unreadable, InputError when it holds no results.
CcxResults read_ccx_dat(const std::filesystem::path& dat);

struct PlyAllowables {
  double fibre_strain = 0.0;       ///< eps_1u
  double transverse_strain = 0.0;  ///< eps_2u
  double shear_strain = 0.0;       ///< gamma_u
};

/// eps_1u, eps_2u, gamma_u from strengths (MPa) and the ply's constants (header comment).
PlyAllowables ply_allowables(const ElasticConstants& c, double fibre_direction_strength,
                             double transverse_strength, double shear_strength);

struct FeaLayerCheck {
  std::string name;
  double fibre_strain_max = 0.0;   ///< largest eps_1 over its plies and elements
  double fibre_strain_min = 0.0;   ///< smallest eps_1
  double fibre_stress_max = 0.0;   ///< largest sigma_1 (MPa)
  double fibre_stress_min = 0.0;   ///< smallest sigma_1 (MPa)
  double fibre_strain_mean = 0.0;  ///< thickness-weighted mean eps_1 over elements and plies
  double failure_factor = 0.0;     ///< max-strain F (header comment)
  double fibre_factor = 0.0;       ///< |eps_1| / eps_1u
  int element = 0;                 ///< the element (1-based) of failure_factor
  std::string mode;                ///< "fibre", "transverse" or "shear" at that element
};

struct FeaCheck {
  std::vector<FeaLayerCheck> layers;
  double failure_factor = 0.0;  ///< first-ply failure factor (max over layers)
  double fibre_factor = 0.0;
  std::string governing;  ///< "<layer>: <mode>"
  int elements = 0;       ///< elements checked
};

/// The check of the plies listed in `plies` (model_plies.csv: element, ply, layer, angle,
/// thickness) against `results`. \throw InputError when an element's integration points do not
/// split evenly over its plies, or a listed element has no results.
/// `skip`: elements left out of the check (e.g. elements_near_free_edges).
FeaCheck check_plies(const CcxResults& results, const CsvTable& plies,
                     const std::vector<std::string>& layer_names, const PlyAllowables& allowables,
                     const std::set<int>& skip = {});

/// The nodes and elements of an input deck (*NODE and *ELEMENT blocks; 1-based ids).
struct InpMesh {
  std::map<int, Vec3> nodes;
  std::map<int, std::vector<int>> elements;
};
/// \throw IoError, InputError for a malformed line.
InpMesh read_inp_mesh(const std::filesystem::path& inp);

/// Elements of a triangle-shell deck (S3/S6: the first three nodes are the corners) whose
/// centroid lies within `distance` (mm) of a corner node on a free edge (an edge of one element):
/// the load introduction at the model's open ends, where the bosses are not modelled.
std::set<int> elements_near_free_edges(const InpMesh& mesh, double distance);

/// Per element (1-based), its membrane strains in the laminate's frame (eps_x along the meridian,
/// eps_y around, gamma_xy): each ply's (its local 2 axis is n x f = -(-s m + c h), so the shear
/// CalculiX prints is turned into the usual sign first) mean (eps_1, eps_2, gamma_12) turned back
/// by its angle a (eps_x = eps_1 c^2 + eps_2 s^2 - gamma_12 s c, eps_y = eps_1 s^2 + eps_2 c^2 +
/// gamma_12 s c, gamma_xy = 2 (eps_1 - eps_2) s c + gamma_12 (c^2 - s^2)), averaged over the plies
/// weighted by their thickness (the strain at mid-thickness when it is linear through the
/// thickness). 	hrow InputError as check_plies.
std::map<int, Vec3d> element_membrane_strains(const CcxResults& results, const CsvTable& plies);

/// Reads a CSV table of numbers written by write_csv (a header row, then numbers).
/// \throw IoError, InputError
CsvTable read_numeric_csv(const std::filesystem::path& file);

}  // namespace windplan
