#pragma once
// The mesh readers of read_mesh_data (geometry/mesh/mesh_io.h), one per format, internal to
// geometry/mesh: OBJ, OFF, PLY (ascii and binary, either byte order) and STL (ascii and binary).
// Each parses a whole file held in memory and throws IoError naming the file (and line).
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh_io.h"

namespace windplan {
namespace mesh_readers {

[[noreturn]] inline void fail(const std::filesystem::path& path, const std::string& what) {
  throw IoError(path.string() + ": " + what);
}

[[noreturn]] inline void fail_line(const std::filesystem::path& path, int line,
                                   const std::string& what) {
  throw IoError(path.string() + ":" + std::to_string(line) + ": " + what);
}

/// PLY bodies and the binary writers: the byte order of this machine.
inline bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

TriangleSoup read_obj(const std::filesystem::path& path, const std::string& data);
TriangleSoup read_off(const std::filesystem::path& path, const std::string& data);
TriangleSoup read_ply(const std::filesystem::path& path, const std::string& data);
/// Binary when the size is 84 + 50 n exactly, else ascii; welded with options.weld_tolerance.
TriangleSoup read_stl(const std::filesystem::path& path, const std::string& data,
                      const MeshReadOptions& options);

}  // namespace mesh_readers
}  // namespace windplan
