#pragma once
// PLY output of the plan's paths (paths.ply) and, until geometry/mesh_io.h's writer is used,
// of the mandrel mesh (mesh.ply). ASCII PLY 1.0, fixed number formatting (deterministic).
//
// paths.ply: element vertex (double x, y, z in mm, int circuit) and element edge (int vertex1,
// vertex2, circuit). Circuits keep their index (>= 0); cut-line k is stored with circuit = -1 - k.
// Each circuit is an open polyline of its dense points; a closed cut-line gets the closing edge.
#include <filesystem>
#include <string>

#include "geometry/mesh.h"
#include "planner/plan.h"

namespace windplan {

/// The paths.ply text.
std::string paths_ply(const WindingPlan& plan);

/// The mesh as ASCII PLY text (vertex x y z, face vertex_indices).
std::string mesh_ply(const Mesh& mesh);

}  // namespace windplan
