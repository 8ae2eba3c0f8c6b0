#pragma once
// Triangle-mesh file input and output: OBJ, PLY (ascii and binary, both endiannesses), STL (ascii
// and binary) and OFF readers; OBJ and PLY writers.
//
// Readers return a TriangleSoup exactly as the file describes it (polygons fan-split into
// triangles (v0, vi, vi+1), indices 0-based); they do not repair anything except that STL, which
// stores every triangle corner separately, is welded: corners closer than
// weld_tolerance * (bounding-box diagonal) become one vertex. Validation and repair are in
// geometry/mesh/mesh_validation.h.
//
// Every reader error is an IoError whose message starts with the file path and names the line
// (text formats) or element (binary formats): missing or empty file, unknown extension, truncated
// binary data (expected against actual size), malformed number, index out of range, NaN or
// infinite coordinate.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct MeshReadOptions {
  /// STL only: corners closer than this fraction of the bounding-box diagonal are welded into one
  /// vertex (dimensionless, >= 0; 0 welds exactly equal positions only).
  double weld_tolerance = 1e-9;

  bool is_valid(std::string* why) const;
};

struct MeshWriteOptions {
  /// PLY only: write ascii instead of binary little endian.
  bool ascii_ply = false;
  /// Significant digits of ascii coordinates (17 round-trips a double exactly).
  int digits = 17;

  bool is_valid(std::string* why) const;
};

/// Extensions read_mesh understands, lower case with the dot: ".obj", ".off", ".ply", ".stl".
const std::vector<std::string>& readable_mesh_extensions();
/// Extensions write_mesh understands: ".obj", ".ply".
const std::vector<std::string>& writable_mesh_extensions();

/// Reads a mesh file; the format is chosen by the extension (case-insensitive).
/// \throw IoError naming the file (and line or element) on any problem, see the file comment.
TriangleSoup read_mesh(const std::filesystem::path& path, const MeshReadOptions& options = {});

/// Same from the file's bytes already in memory (fuzzing, tests); `path` names it in messages and
/// its extension chooses the format.
TriangleSoup read_mesh_data(const std::string& data, const std::filesystem::path& path,
                            const MeshReadOptions& options = {});

/// Writes a mesh as OBJ or PLY (by extension) through write_file_atomically.
/// \throw IoError for an unknown extension or when the file cannot be written.
void write_mesh(const std::filesystem::path& path, const TriangleSoup& soup,
                const MeshWriteOptions& options = {});
void write_mesh(const std::filesystem::path& path, const Mesh& mesh,
                const MeshWriteOptions& options = {});

/// Welds points closer than `tolerance` (absolute, in the points' unit) into one; triangles are
/// re-indexed, the first point of each cluster is kept, order of first appearance is preserved.
/// Used by the STL reader; exposed for tests and for callers that build soups themselves.
TriangleSoup weld_vertices(const TriangleSoup& soup, double tolerance);

}  // namespace windplan
