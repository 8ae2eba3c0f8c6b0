#pragma once
// The laminate for a stress engineer: per face of the mandrel mesh and per layer, the fibre
// angles measured from the laid paths and the layer's thickness, as CSV (laminate.csv) and as a
// VTK unstructured grid with cell data (laminate.vtu, ASCII XML; ParaView and VTK's
// vtkXMLUnstructuredGridReader open it).
//
// Angles. At a face with unit normal n the meridian direction m is the spindle axis direction
// projected onto the face plane, and h = m x n the hoop direction (the way the mandrel's angle
// increases, right-handed about the axis). A path segment with direction t, taken with t . m >= 0
// (a fibre has no direction), makes the signed angle atan2(t . h, t . m) in (-90, 90] deg with the
// meridian: the +alpha family of a helical layer (the out passes) has positive angles, the
// -alpha family (the return passes) negative ones; a hoop layer's passes are the +-89.x deg
// families. Every segment of the layer's circuits (passes and turnarounds) is assigned to the
// face of `mesh` nearest its midpoint (a layer wound on the surface built by the layers under it
// lies a few mm above `mesh`: its faces are found along the normal), and per face and family the
// angle is the length-weighted mean of its segments' angles. A face that no segment of a family
// crosses has angle 0 and length 0 for that family (the length arrays tell them apart).
// Thickness is given per face by the caller (the thickness model,
// planner/layup/laminate_thickness.h).
//
// laminate.csv: one row per face and layer: face, layer (0 innermost), thickness [mm],
// angle_plus [deg], angle_minus [deg], length_plus [mm], length_minus [mm], centroid x, y, z [mm].
// laminate.vtu: the mesh's points and triangles; cell data "meridian" (3 components: m above),
// "total_thickness_mm", and per layer k (1-based, innermost first) with its sanitised name:
// "L<k>_<name>_thickness_mm", "..._angle_plus_deg", "..._angle_minus_deg",
// "..._length_plus_mm", "..._length_minus_mm".
#include <filesystem>
#include <string>
#include <vector>

#include "export/files/csv.h"
#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "planner/plan/plan.h"

namespace windplan {

/// Per face of a mesh: the +alpha and -alpha families' mean angles and lengths.
struct FaceFibreAngles {
  std::vector<double> angle_plus;    ///< deg, in (0, 90]; 0 where length_plus is 0
  std::vector<double> angle_minus;   ///< deg, in (-90, 0]; 0 where length_minus is 0
  std::vector<double> length_plus;   ///< mm of +alpha path in the face
  std::vector<double> length_minus;  ///< mm of -alpha path in the face
};

/// Measures the fibre angles of `circuits` per face of `mesh` (header comment).
/// \throw InputError for an empty mesh.
FaceFibreAngles measure_face_angles(const Mesh& mesh, const SpindleAxis& axis,
                                    const std::vector<Circuit>& circuits);

/// One layer of the laminate on the faces of the mesh.
struct LaminateLayerFaces {
  std::string name;               ///< e.g. "hoop1"
  std::string kind;               ///< "helical" or "hoop"
  std::vector<double> thickness;  ///< per face (mm)
  FaceFibreAngles angles;
};

/// The unit meridian direction in the plane of each face (header comment).
std::vector<Vec3> face_meridians(const Mesh& mesh, const SpindleAxis& axis);

/// laminate.csv (header comment). \throw InputError when a layer's arrays do not match the mesh.
CsvTable laminate_table(const Mesh& mesh, const std::vector<LaminateLayerFaces>& layers);

/// laminate.vtu as text (header comment). \throw InputError as laminate_table.
std::string laminate_vtu(const Mesh& mesh, const SpindleAxis& axis,
                         const std::vector<LaminateLayerFaces>& layers);

/// Writes laminate.csv and laminate.vtu into `dir` (atomically); returns the names written.
/// \throw IoError, InputError as above.
std::vector<std::string> write_laminate_fea(const std::filesystem::path& dir, const Mesh& mesh,
                                            const SpindleAxis& axis,
                                            const std::vector<LaminateLayerFaces>& layers);

}  // namespace windplan
