// FlipOut and windplan side by side in ONE process on one core (bench/README.md, session 23):
// not part of the build, since it links geometry-central, which the repository never vendors.
// Build geometry-central (github nmwsharp/geometry-central, e.g. 56152a8) in a scratch directory
// GC outside the repository, then from the repository's root after its own build:
//   L=$(find build/geometry -name '*.a')
//   g++ -O3 -DNDEBUG -std=c++17 -I. -I$GC/include -I$GC/deps/happly -I$GC/deps/nanoflann/include \
//     -I$GC/deps/nanort/include -isystem /usr/include/eigen3 bench/peers/flipout_side_by_side.cpp \
//     -o /tmp/side_by_side $L $L $GC/build/src/libgeometry-central.a -ltbb -lgmp -lmpfr -lpthread
//   taskset -c 1 /tmp/side_by_side MESH PAIRS REFERENCE ROUNDS [blocks] [local]
// FlipOut: the calls of ../shared/tools/flipout_pairs.cpp (one FlipEdgeNetwork per mesh with
// supportRewinding; per pair shortestEdgePath, reinitializePath, iterativeShorten, length,
// rewind). windplan: geodesic_between on a GeodesicContext with default options, the call
// bench_geodesic times. PAIRS: "s t" per line (bench_geodesic --write-pairs); REFERENCE: "s t d"
// per line, the exact distances of an independent program (geometry-central's MMP).
// Default: the two alternate pair by pair, the order flipped every pair and every round;
// `blocks`: all pairs of one, then all of the other, the order flipped every round. Each pair
// keeps its least thread CPU over the rounds. Prints every pair (s t windplan_length
// flipout_length windplan_ms flipout_ms) and, on stderr, median / mean / p90 and the ratios.
#include <time.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "geometrycentral/surface/flip_geodesics.h"
#include "geometrycentral/surface/mesh_graph_algorithms.h"
#include "geometrycentral/surface/meshio.h"

#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"

static double thread_ms() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

int main(int argc, char** argv) {
  namespace gc = geometrycentral::surface;
  std::vector<std::pair<int, int>> pairs;
  {
    std::ifstream in(argv[2]);
    int s, t;
    while (in >> s >> t) pairs.push_back({s, t});
  }
  std::vector<double> mmp;
  {
    std::ifstream in(argv[3]);
    int s, t;
    double d;
    while (in >> s >> t >> d) mmp.push_back(d);
  }
  const int rounds = std::atoi(argv[4]);
  const int n = static_cast<int>(pairs.size());
  // FlipOut as in flipout_pairs.cpp
  std::unique_ptr<gc::ManifoldSurfaceMesh> fmesh;
  std::unique_ptr<gc::VertexPositionGeometry> geom;
  std::tie(fmesh, geom) = gc::readManifoldSurfaceMesh(argv[1]);
  geom->requireEdgeLengths();
  gc::FlipEdgeNetwork network(*fmesh, *geom, {});
  network.supportRewinding = true;
  network.posGeom = geom.get();
  auto flipout = [&](int s, int t, double* len) {
    const double c1 = thread_ms();
    std::vector<gc::Halfedge> path =
        gc::shortestEdgePath(*geom, fmesh->vertex(s), fmesh->vertex(t));
    network.reinitializePath({path});
    network.iterativeShorten();
    *len = network.length();
    network.rewind();
    network.isMarkedVertex[network.mesh.vertex(s)] = false;
    network.isMarkedVertex[network.mesh.vertex(t)] = false;
    return thread_ms() - c1;
  };
  // windplan as bench_geodesic
  const windplan::Mesh mesh = windplan::build_mesh(windplan::read_mesh(argv[1]), false);
  const windplan::GeodesicContext ctx(mesh);
  windplan::GeodesicOptions options;
  // `local`: windplan's local mode (exact_windows off: the locally shortest geodesic from the
  // local starts, no window search), the mode planners use from a good start.
  bool blocks = false;
  for (int i = 5; i < argc; ++i) {
    blocks = blocks || std::string(argv[i]) == "blocks";
    if (std::string(argv[i]) == "local") options.exact_windows = false;
  }
  auto wp = [&](int s, int t, double* len) {
    const double c1 = thread_ms();
    const auto r = windplan::geodesic_between(ctx, windplan::SurfacePoint::at_vertex(s),
                                              windplan::SurfacePoint::at_vertex(t), options);
    const double c = thread_ms() - c1;
    *len = r.summary.final_length;
    return c;
  };
  {
    double l;
    flipout(pairs[0].first, pairs[0].second, &l);
    wp(pairs[0].first, pairs[0].second, &l);
  }  // warm-up
  std::vector<double> bf(n, 1e300), bw(n, 1e300), lf(n), lw(n);
  for (int r = 0; r < rounds && blocks; ++r) {
    for (int k = 0; k < 2; ++k) {
      if ((r + k) % 2 == 0)
        for (int i = 0; i < n; ++i)
          bf[i] = std::min(bf[i], flipout(pairs[i].first, pairs[i].second, &lf[i]));
      else
        for (int i = 0; i < n; ++i)
          bw[i] = std::min(bw[i], wp(pairs[i].first, pairs[i].second, &lw[i]));
    }
  }
  for (int r = 0; r < rounds && !blocks; ++r) {
    for (int i = 0; i < n; ++i) {
      const auto [s, t] = pairs[i];
      if ((r + i) % 2 == 0) {
        bf[i] = std::min(bf[i], flipout(s, t, &lf[i]));
        bw[i] = std::min(bw[i], wp(s, t, &lw[i]));
      } else {
        bw[i] = std::min(bw[i], wp(s, t, &lw[i]));
        bf[i] = std::min(bf[i], flipout(s, t, &lf[i]));
      }
    }
  }
  int ef = 0, ew = 0;
  for (int i = 0; i < n; ++i) {
    ef += std::abs(lf[i] - mmp[i]) <= 1e-9 * mmp[i];
    ew += std::abs(lw[i] - mmp[i]) <= 1e-9 * mmp[i];
    std::printf("%d %d %.17g %.17g %.6f %.6f\n", pairs[i].first, pairs[i].second, lw[i], lf[i],
                bw[i], bf[i]);
  }
  auto stats = [](std::vector<double> v, double* med, double* mean, double* p90) {
    std::sort(v.begin(), v.end());
    *med = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    double s = 0;
    for (double x : v) s += x;
    *mean = s / v.size();
    *p90 = v[std::min(v.size() - 1, static_cast<size_t>(std::ceil(0.9 * v.size())) - 1)];
  };
  double wm, wmean, wp90, fm, fmean, fp90;
  stats(bw, &wm, &wmean, &wp90);
  stats(bf, &fm, &fmean, &fp90);
  std::fprintf(stderr,
               "%s rounds %d | windplan %.3f / %.3f / %.3f ms exact %d/%d | FlipOut %.3f / %.3f / "
               "%.3f ms exact %d/%d | ratio median %.3f mean %.3f\n",
               argv[1], rounds, wm, wmean, wp90, ew, n, fm, fmean, fp90, ef, n, wm / fm,
               wmean / fmean);
}
