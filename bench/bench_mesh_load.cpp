// Loading speed: read (parse) and connectivity (halfedge Mesh) times of the benchmark meshes,
// plus check_mesh. Prints the best of 3 runs of each step. Needs ../shared/data/meshes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"

using namespace windplan;
using Clock = std::chrono::steady_clock;

static double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

int main() {
  const std::filesystem::path root = WINDPLAN_SHARED_MESHES;
  const char* files[] = {"derived/bunny-remesh-20k.obj", "derived/bunny-remesh-100k.obj",
                         "derived/bunny-remesh-300k.obj", "kitten-106k.obj"};
  std::printf("%-32s %9s %9s %9s %9s %8s %8s %8s\n", "mesh", "MB", "read_ms", "conn_ms", "check_ms",
              "V", "F", "total");
  for (const char* name : files) {
    const auto path = root / name;
    if (!std::filesystem::exists(path)) {
      std::printf("%-32s (missing: %s)\n", name, path.c_str());
      continue;
    }
    double read = 1e30, conn = 1e30, check = 1e30;
    int nv = 0, nf = 0;
    for (int run = 0; run < 3; ++run) {
      auto t = Clock::now();
      TriangleSoup soup = read_mesh(path);
      read = std::min(read, ms_since(t));
      t = Clock::now();
      const MeshHealth h = check_mesh(soup);
      check = std::min(check, ms_since(t));
      t = Clock::now();
      const Mesh mesh(std::move(soup));
      conn = std::min(conn, ms_since(t));
      nv = mesh.num_vertices();
      nf = mesh.num_faces();
      if (h.num_faces != nf) return 1;
    }
    std::printf("%-32s %9.1f %9.1f %9.1f %9.1f %8d %8d %8.1f\n", name,
                std::filesystem::file_size(path) / 1e6, read, conn, check, nv, nf, read + conn);
  }
  return 0;
}
