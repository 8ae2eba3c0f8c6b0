#pragma once
// PLY output of the plan's paths (paths.ply; mesh.ply is written by geometry/mesh/mesh_io.h's
// write_mesh). ASCII PLY 1.0, fixed number formatting (deterministic).
//
// paths.ply: element vertex (double x, y, z in mm, int circuit) and element edge (int vertex1,
// vertex2, circuit). Circuits keep their index (>= 0); cut-line k is stored with circuit = -1 - k.
// Each circuit is an open polyline of its dense points; a closed cut-line gets the closing edge.
#include <filesystem>
#include <string>

#include "geometry/mesh/mesh.h"
#include "planner/plan/plan.h"

namespace windplan {

/// The paths.ply text.
std::string paths_ply(const WindingPlan& plan);

}  // namespace windplan
