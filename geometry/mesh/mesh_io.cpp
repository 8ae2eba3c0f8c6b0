#include "geometry/mesh/mesh_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/input_file.h"
#include "geometry/mesh/mesh_readers.h"

namespace windplan {

using mesh_readers::fail;
using mesh_readers::host_is_little_endian;

namespace {

// ---------------------------------------------------------------------------------------------
// Shared helpers

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// The whole file in one read: parsing a memory buffer with pointers is what makes a 16 MB OBJ
// load in tens of milliseconds instead of seconds with iostreams.
std::string read_whole_file(const std::filesystem::path& path) {
  // A regular file of bounded size only (geometry/base/input_file.h): a FIFO or /dev/zero is
  // refused at once, named as such.
  std::string data = read_input_file(path, kMeshFileCap, "a mesh file (OBJ, OFF, PLY or STL)");
  if (data.empty()) fail(path, "empty file");
  return data;
}

// ---------------------------------------------------------------------------------------------
// Writers

void write_obj(std::ostream& out, const std::vector<Vec3>& pts, const std::vector<Tri>& tris,
               int digits) {
  char buf[128];
  std::string chunk;
  chunk.reserve(1 << 16);
  chunk += "# written by windplan\n";
  for (const Vec3& p : pts) {
    std::snprintf(buf, sizeof buf, "v %.*g %.*g %.*g\n", digits, p.x(), digits, p.y(), digits,
                  p.z());
    chunk += buf;
    if (chunk.size() > (1 << 16) - 256) {
      out << chunk;
      chunk.clear();
    }
  }
  for (const Tri& t : tris) {
    std::snprintf(buf, sizeof buf, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
    chunk += buf;
    if (chunk.size() > (1 << 16) - 256) {
      out << chunk;
      chunk.clear();
    }
  }
  out << chunk;
}

template <class T>
void put_le(std::string* s, T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (!host_is_little_endian()) std::reverse(b, b + sizeof(T));
  s->append(reinterpret_cast<const char*>(b), sizeof(T));
}

void write_ply(std::ostream& out, const std::vector<Vec3>& pts, const std::vector<Tri>& tris,
               bool ascii, int digits) {
  std::string s = "ply\nformat ";
  s += ascii ? "ascii" : "binary_little_endian";
  s += " 1.0\ncomment written by windplan\nelement vertex " + std::to_string(pts.size()) +
       "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
       std::to_string(tris.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  char buf[128];
  if (ascii) {
    for (const Vec3& p : pts) {
      std::snprintf(buf, sizeof buf, "%.*g %.*g %.*g\n", digits, p.x(), digits, p.y(), digits,
                    p.z());
      s += buf;
    }
    for (const Tri& t : tris) {
      std::snprintf(buf, sizeof buf, "3 %d %d %d\n", t[0], t[1], t[2]);
      s += buf;
    }
  } else {
    s.reserve(s.size() + 24 * pts.size() + 13 * tris.size());
    for (const Vec3& p : pts) {
      put_le(&s, p.x());
      put_le(&s, p.y());
      put_le(&s, p.z());
    }
    for (const Tri& t : tris) {
      put_le(&s, static_cast<std::uint8_t>(3));
      for (int k = 0; k < 3; ++k) put_le(&s, static_cast<std::int32_t>(t[k]));
    }
  }
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

void write_any(const std::filesystem::path& path, const std::vector<Vec3>& pts,
               const std::vector<Tri>& tris, const MeshWriteOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("mesh write options: " + why);
  const std::string ext = lower(path.extension().string());
  if (ext == ".obj") {
    write_file_atomically(path, [&](std::ostream& o) { write_obj(o, pts, tris, options.digits); });
  } else if (ext == ".ply") {
    write_file_atomically(
        path, [&](std::ostream& o) { write_ply(o, pts, tris, options.ascii_ply, options.digits); },
        true);
  } else {
    fail(path, "cannot write mesh format '" + (ext.empty() ? std::string("(none)") : ext) +
                   "' (supported: " + join(writable_mesh_extensions()) + ")");
  }
}

}  // namespace

bool MeshReadOptions::is_valid(std::string* why) const {
  if (!(weld_tolerance >= 0.0) || !std::isfinite(weld_tolerance)) {
    if (why) *why = "weld_tolerance must be a finite number >= 0";
    return false;
  }
  return true;
}

bool MeshWriteOptions::is_valid(std::string* why) const {
  if (digits < 1 || digits > 17) {
    if (why) *why = "digits must be in [1, 17]";
    return false;
  }
  return true;
}

const std::vector<std::string>& readable_mesh_extensions() {
  static const std::vector<std::string> e = {".obj", ".off", ".ply", ".stl"};
  return e;
}

namespace {

// Options and extension of a read; IoError/ConfigError as documented for read_mesh.
void check_mesh_format(const std::filesystem::path& path, const MeshReadOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("mesh read options: " + why);
  const std::string ext = lower(path.extension().string());
  const auto& known = readable_mesh_extensions();
  if (std::find(known.begin(), known.end(), ext) == known.end()) {
    fail(path, "unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : ext) +
                   "' (supported: " + join(known) + ")");
  }
}

}  // namespace

const std::vector<std::string>& writable_mesh_extensions() {
  static const std::vector<std::string> e = {".obj", ".ply"};
  return e;
}

TriangleSoup read_mesh(const std::filesystem::path& path, const MeshReadOptions& options) {
  std::error_code ec;
  // (Before the extension: a folder named "tube" is not an "unknown mesh format".)
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, not a mesh file");
  check_mesh_format(path, options);
  return read_mesh_data(read_whole_file(path), path, options);
}

TriangleSoup read_mesh_data(const std::string& data, const std::filesystem::path& path,
                            const MeshReadOptions& options) {
  check_mesh_format(path, options);
  const std::string ext = lower(path.extension().string());
  if (data.empty()) fail(path, "empty file");
  TriangleSoup soup;
  if (ext == ".obj")
    soup = mesh_readers::read_obj(path, data);
  else if (ext == ".off")
    soup = mesh_readers::read_off(path, data);
  else if (ext == ".ply")
    soup = mesh_readers::read_ply(path, data);
  else
    soup = mesh_readers::read_stl(path, data, options);
  if (soup.triangles.empty()) fail(path, "the file contains no faces");
  return soup;
}

void write_mesh(const std::filesystem::path& path, const TriangleSoup& soup,
                const MeshWriteOptions& options) {
  write_any(path, soup.points, soup.triangles, options);
}

void write_mesh(const std::filesystem::path& path, const Mesh& mesh,
                const MeshWriteOptions& options) {
  write_any(path, mesh.points(), mesh.triangles(), options);
}

TriangleSoup weld_vertices(const TriangleSoup& soup, double tolerance) {
  const std::size_t n = soup.points.size();
  std::vector<int> remap(n, -1);
  TriangleSoup out;
  out.points.reserve(n / 4 + 16);
  if (!(tolerance > 0.0)) {
    // Exact: hash the bit patterns (with -0 folded into +0).
    struct Key {
      double x, y, z;
      bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
    };
    struct Hash {
      std::size_t operator()(const Key& k) const {
        std::size_t h = 1469598103934665603ull;
        for (double d : {k.x, k.y, k.z}) {
          if (d == 0.0) d = 0.0;
          std::uint64_t u;
          std::memcpy(&u, &d, 8);
          h = (h ^ u) * 1099511628211ull;
          h ^= h >> 29;
        }
        return h;
      }
    };
    std::unordered_map<Key, int, Hash> index;
    index.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = soup.points[i];
      const auto it = index.emplace(Key{p.x(), p.y(), p.z()}, static_cast<int>(out.points.size()));
      if (it.second) out.points.push_back(p);
      remap[i] = it.first->second;
    }
  } else {
    // Grid of cell size `tolerance`: a point within tolerance of another lies in one of the 27
    // cells around it. Each welded vertex is stored in its cell's chain.
    const double inv = 1.0 / tolerance;
    auto cell_of = [inv](const Vec3& p) {
      return std::array<long long, 3>{static_cast<long long>(std::floor(p.x() * inv)),
                                      static_cast<long long>(std::floor(p.y() * inv)),
                                      static_cast<long long>(std::floor(p.z() * inv))};
    };
    auto hash = [](long long x, long long y, long long z) {
      std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
      h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
      h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
      return h;
    };
    std::unordered_map<std::uint64_t, int> head;  // cell hash -> last welded vertex in chain
    head.reserve(n);
    std::vector<int> chain;  // per welded vertex: previous in same hash
    const double tol2 = tolerance * tolerance;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = soup.points[i];
      const auto c = cell_of(p);
      int found = -1;
      for (int dx = -1; dx <= 1 && found < 0; ++dx)
        for (int dy = -1; dy <= 1 && found < 0; ++dy)
          for (int dz = -1; dz <= 1 && found < 0; ++dz) {
            const auto it = head.find(hash(c[0] + dx, c[1] + dy, c[2] + dz));
            if (it == head.end()) continue;
            for (int w = it->second; w >= 0; w = chain[w]) {
              if ((out.points[w] - p).squaredNorm() <= tol2) {
                found = w;
                break;
              }
            }
          }
      if (found < 0) {
        found = static_cast<int>(out.points.size());
        out.points.push_back(p);
        auto it = head.find(hash(c[0], c[1], c[2]));
        if (it == head.end()) {
          head.emplace(hash(c[0], c[1], c[2]), found);
          chain.push_back(-1);
        } else {
          chain.push_back(it->second);
          it->second = found;
        }
      }
      remap[i] = found;
    }
  }
  out.triangles.reserve(soup.triangles.size());
  for (const Tri& t : soup.triangles)
    out.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return out;
}

}  // namespace windplan
