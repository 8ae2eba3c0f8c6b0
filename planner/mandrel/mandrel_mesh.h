#pragma once
// The mandrel of a job as a windplan Mesh, in millimetres: the single place that turns a job's
// `mandrel:` section into the surface every later stage works on. It dispatches on
// MandrelOptions::source "mesh" (a triangle-mesh file: OBJ, PLY, STL, OFF). CAD and parametric
// sources are built by planner/mandrel/mandrel_builder.h, which calls this for mesh files.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_validation.h"
#include "planner/job/job.h"

namespace windplan {

/// Loads the mandrel described by `mandrel`: reads the file, scales it from mandrel.units to mm,
/// checks it and, when mandrel.repair is set, repairs what is safe
/// (geometry/mesh/mesh_validation.h). \param health_out if given, receives the health of the mesh
/// as read (in mm, before repair) \param changes    if given, receives the repairs made, in plain
/// words \throw IoError for an unreadable file, TopologyError naming elements when the mesh cannot
///        be made a valid oriented 2-manifold, ConfigError for an unsupported source.
Mesh load_mandrel_mesh(const MandrelOptions& mandrel, MeshHealth* health_out = nullptr,
                       std::vector<std::string>* changes = nullptr);

/// The triangle soup of a mesh-file mandrel in mm, without validation (for reports on broken
/// meshes). \throw IoError, ConfigError as above.
TriangleSoup load_mandrel_soup(const MandrelOptions& mandrel);

}  // namespace windplan
