// The target bound (geometry/geodesic/target_bound.h) and the window search that uses it,
// against CGAL's exact distances on unusual meshes: holes and a slit, rough terrain, needle and
// cap triangles, a monkey saddle, spikes, a sphere, a coarse torus, an octahedron, two triangles,
// two components, an open cylinder. The bound is checked at vertices and at points along edges
// (where window keys read it), always built (min_detour 1); the searches with a finite upper
// bound just above and just below the distance, with landmarks, and resumed from target to
// target. (Written in session 15's review; it fails when the level set's distance in step 4 is
// taken from the ends of its segment only.)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "geometry/geodesic/exact_geodesic.h"
#include "geometry/geodesic/geodesic_windows.h"
#include "geometry/geodesic/target_bound.h"
#include "geometry/geodesic/window_landmarks.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The soup with the vertices no triangle uses dropped (the others renumbered in order).
TriangleSoup compact(const TriangleSoup& s) {
  std::vector<int> used(s.points.size(), -1);
  TriangleSoup out;
  for (const Tri& t : s.triangles)
    for (int v : t)
      if (used[v] < 0) {
        used[v] = static_cast<int>(out.points.size());
        out.points.push_back(s.points[v]);
      }
  for (const Tri& t : s.triangles) out.triangles.push_back({used[t[0]], used[t[1]], used[t[2]]});
  return out;
}

TriangleSoup grid_with_holes(int n, double size, double bump) {
  TriangleSoup g = test::grid(n, n, size / n);
  std::set<std::pair<int, int>> holes;
  // 2x2 and 3x1 holes, separated.
  for (int i = 3; i < 6; ++i) holes.insert({i, 4});
  for (int i = 10; i < 12; ++i)
    for (int j = 8; j < 10; ++j) holes.insert({i, j});
  for (int j = 2; j < 12; ++j) holes.insert({7, j});  // a long slit
  TriangleSoup s;
  s.points = g.points;
  for (Vec3& p : s.points) p.z() = bump * std::sin(p.x() * 1.3) * std::cos(p.y() * 0.9);
  int k = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool hole = holes.count({i, j}) > 0;
      if (!hole) {
        s.triangles.push_back(g.triangles[k]);
        s.triangles.push_back(g.triangles[k + 1]);
      }
      k += 2;
    }
  return compact(s);
}

// A rough terrain: strong random heights (saddles everywhere, steep thin faces).
TriangleSoup rough_terrain(int n, double size, double amp, unsigned seed) {
  TriangleSoup s = test::grid(n, n, size / n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  for (Vec3& p : s.points) p.z() += u(rng);
  return s;
}

// Hills with cap triangles: some vertices moved almost onto the opposite edge.
TriangleSoup needles(int n, double size) {
  TriangleSoup s = test::hills(n, size);
  const double h = size / n;
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int k = 0; k < 6; ++k) {
    const int i = 3 + 5 * k, j = 4 + 4 * k;
    if (i + 1 >= n || j + 2 >= n) break;
    Vec3& p = s.points[id(i, j + 1)];
    const Vec3 a = s.points[id(i, j)], b = s.points[id(i + 1, j + 1)];
    p = 0.5 * (a + b) + Vec3(-1e-7 * h, 1e-7 * h, 1e-6 * h);
  }
  return s;
}

// A cone / strong saddle: a grid whose centre vertex carries a monkey saddle.
TriangleSoup monkey(int n, double size, double amp) {
  TriangleSoup s = test::grid(n, n, size / n);
  for (Vec3& p : s.points) {
    const double x = p.x() - size / 2, y = p.y() - size / 2;
    const double r = std::hypot(x, y), th = std::atan2(y, x);
    p.z() = amp * std::sin(3 * th) * r * std::exp(-r * r / (0.1 * size * size));
  }
  return s;
}

// A sharp cone (a spherical vertex with small cone angle) on a disc plus a spike.
TriangleSoup spikes(int n, double size) {
  TriangleSoup s = test::grid(n, n, size / n);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(1, n - 1);
  for (int k = 0; k < 12; ++k) {
    const int i = pick(rng), j = pick(rng);
    s.points[j * (n + 1) + i].z() += (k % 2 ? 1.0 : -1.0) * 3.0 * size / n;
  }
  return s;
}

TriangleSoup two_components() {
  TriangleSoup a = test::hills(12, 6.0);
  TriangleSoup b = test::uv_sphere(1.0, 10, 6);
  const int off = static_cast<int>(a.points.size());
  for (Vec3 p : b.points) a.points.push_back(p + Vec3(10, 0, 0));
  for (Tri t : b.triangles) a.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  return a;
}

struct Stats {
  long pairs = 0, bound_pairs = 0, vertex_checks = 0, edge_checks = 0, searches = 0;
  double worst_vertex = 0, worst_edge = 0, worst_search = 0;
};

void stress(const char* what, const TriangleSoup& soup, int count, unsigned seed) {
  const Mesh mesh(soup);
  const WindowMesh wm = prepare_window_mesh(mesh);
  ExactGeodesic cgal(mesh);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
  TargetBoundOptions bo;
  bo.min_detour = 1.0;
  bo.min_edges = 0.0;
  WindowSearchOptions opt;
  opt.target_bound.min_detour = 1.0;
  WindowSearchOptions off;
  off.use_target_bound = false;
  const Landmarks lm = compute_landmarks(mesh, wm, 4);
  const std::vector<int>& local = wm.order.vertex_to_local;
  std::vector<SurfacePoint> verts;
  for (int v = 0; v < mesh.num_vertices(); ++v) verts.push_back(SurfacePoint::at_vertex(v));
  // Edge points: every interior halfedge h < 3F with from < to, at t = 0.25, 0.5, 0.8.
  std::vector<SurfacePoint> epts;
  const double ts[] = {0.13, 0.5, 0.87};
  for (int h = 0; h < mesh.num_interior_halfedges(); ++h) {
    if (mesh.from(h) > mesh.to(h) && !mesh.is_boundary_halfedge(mesh.twin(h))) continue;
    for (double t : ts) epts.push_back(SurfacePoint::on_edge(h, t));
  }
  std::vector<SurfacePoint> all = verts;
  all.insert(all.end(), epts.begin(), epts.end());
  Stats st;
  TargetBound bound;
  for (int i = 0; i < count; ++i) {
    int s = pick(rng), t = pick(rng);
    if (i == 0) t = s;  // source == target
    ++st.pairs;
    const std::vector<double> fs = cgal.distances(SurfacePoint::at_vertex(s), all);
    const std::vector<double> ft = cgal.distances(SurfacePoint::at_vertex(t), all);
    const double D = fs[t];
    build_target_bound(wm, local[s], local[t], kInf, bo, &bound);
    // U is a real path's length (edges and diagonals): never below D. The vertices checked are
    // chosen by max(U, D), so that a U below D cannot leave the check empty.
    if (s != t && std::isfinite(D)) {
      EXPECT_GE(bound.upper, D * (1.0 - 1e-12)) << what << " " << s << "->" << t << ": U < D";
    }
    const double region = std::max(bound.upper, std::isfinite(D) ? D : 0.0);
    if (bound.active) {
      ++st.bound_pairs;
      for (int v = 0; v < mesh.num_vertices(); ++v) {
        if (!(fs[v] + ft[v] <= region)) continue;
        ++st.vertex_checks;
        const double h = bound.at(local[v]);
        const double excess = (h - ft[v]) / std::max(D, 1e-300);
        st.worst_vertex = std::max(st.worst_vertex, excess);
        EXPECT_LE(h, ft[v] + 1e-10 * D) << what << " " << s << "->" << t << " v " << v
                                        << " h " << h << " d " << ft[v] << " R " << bound.radius
                                        << " L " << bound.slope << " E " << bound.excess;
      }
      for (std::size_t k = 0; k < epts.size(); ++k) {
        const std::size_t j = verts.size() + k;
        if (!(fs[j] + ft[j] <= region)) continue;
        const int he = epts[k].element;
        const double ha = bound.at(local[mesh.from(he)]), hb = bound.at(local[mesh.to(he)]);
        if (!(ha > -kInf && hb > -kInf)) continue;
        ++st.edge_checks;
        const double h = ha + epts[k].t * (hb - ha);
        st.worst_edge = std::max(st.worst_edge, (h - ft[j]) / std::max(D, 1e-300));
        EXPECT_LE(h, ft[j] + 1e-10 * D) << what << " " << s << "->" << t << " edge " << he
                                        << " t " << epts[k].t;
      }
    }
    if (s == t) continue;
    for (int variant = 0; variant < 4; ++variant) {
      WindowSearchOptions o = opt;
      const Landmarks* l = nullptr;
      bool expect_found = std::isfinite(D);
      if (variant == 1) o.upper_bound = std::isfinite(D) ? D * (1 + 1e-6) : 50.0;
      if (variant == 2) {
        if (!std::isfinite(D)) continue;
        o.upper_bound = D * (1 - 1e-6);
        expect_found = false;
      }
      if (variant == 3) l = &lm;
      const WindowSearchResult r = shortest_path_by_windows(mesh, wm, s, t, o, l);
      ++st.searches;
      EXPECT_EQ(r.found, expect_found) << what << " " << s << "->" << t << " variant " << variant;
      if (r.found && expect_found) {
        st.worst_search = std::max(st.worst_search, std::abs(r.distance - D) / D);
        EXPECT_NEAR(r.distance, D, 1e-9 * D) << what << " " << s << "->" << t << " variant "
                                             << variant;
      }
    }
  }
  // Resumed searches from a few sources to many targets.
  for (int i = 0; i < 4; ++i) {
    const int s = pick(rng);
    std::vector<int> targets;
    for (int k = 0; k < 12; ++k) targets.push_back(pick(rng));
    targets.push_back(s);
    const std::vector<double> fs = cgal.distances(SurfacePoint::at_vertex(s), verts);
    for (int variant = 0; variant < 2; ++variant) {
      WindowSearchOptions o = opt;
      if (variant == 1) o.upper_bound = 1.0 + *std::max_element(fs.begin(), fs.end(), [](double a, double b) {
        return (std::isfinite(a) ? a : 0) < (std::isfinite(b) ? b : 0); });
      const std::vector<WindowSearchResult> r = shortest_paths_by_windows(mesh, wm, s, targets, o);
      for (std::size_t k = 0; k < targets.size(); ++k) {
        const int t = targets[k];
        ++st.searches;
        if (t == s || !std::isfinite(fs[t]) || (variant == 1 && !(fs[t] < o.upper_bound))) {
          EXPECT_FALSE(r[k].found) << what;
          continue;
        }
        EXPECT_TRUE(r[k].found) << what << " resumed " << s << "->" << t;
        if (r[k].found) {
          st.worst_search = std::max(st.worst_search, std::abs(r[k].distance - fs[t]) / fs[t]);
          EXPECT_NEAR(r[k].distance, fs[t], 1e-9 * fs[t]) << what << " resumed " << s << "->" << t;
        }
      }
    }
  }
  std::printf("%-14s V %d pairs %ld bound %ld vchecks %ld echecks %ld searches %ld worst v %.3g e %.3g search %.3g\n",
              what, mesh.num_vertices(), st.pairs, st.bound_pairs, st.vertex_checks,
              st.edge_checks, st.searches, st.worst_vertex, st.worst_edge, st.worst_search);
}

// A plane jittered within itself, flat or bumpy: many pairs of faces whose unfolding is not
// convex, which must get no diagonal. (Accepting them puts U up to 9 % below D on the rough
// terrain: the U >= D check above fails there, as the review found no test did before.)
TriangleSoup jitter_plane(int n, double size, double amount, unsigned seed, double bump) {
  TriangleSoup s = test::grid(n, n, size / n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount * size / n, amount * size / n);
  for (Vec3& p : s.points) {
    p.x() += u(rng);
    p.y() += u(rng);
    p.z() = bump * std::sin(p.x()) * std::sin(p.y());
  }
  return s;
}

// A bumpy plane with a zero-width slit: the vertices along x = n/2, 3 <= y <= n-3 doubled, the
// faces left of the slit using the copies.
TriangleSoup slit(int n, double size, double bump) {
  TriangleSoup s = test::grid(n, n, size / n);
  for (Vec3& p : s.points) p.z() = bump * std::sin(p.x() * 1.1) * std::cos(p.y() * 0.7);
  const auto id = [n](int i, int j) { return j * (n + 1) + i; };
  std::map<int, int> copy;
  for (int j = 3; j <= n - 3; ++j) {
    copy[id(n / 2, j)] = static_cast<int>(s.points.size());
    s.points.push_back(s.points[id(n / 2, j)]);
  }
  const double cut = s.points[id(n / 2, 0)].x();
  for (Tri& t : s.triangles) {
    const Vec3 c = (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3.0;
    if (c.x() < cut)
      for (int& v : t)
        if (copy.count(v)) v = copy[v];
  }
  return s;
}

TEST(TargetBoundStress, JitteredPlane) { stress("jitter", jitter_plane(16, 8.0, 0.45, 1, 0.0), 40, 21); }
TEST(TargetBoundStress, JitteredBumps) { stress("jitter bumps", jitter_plane(16, 8.0, 0.45, 2, 0.8), 40, 22); }
TEST(TargetBoundStress, Slit) { stress("slit", slit(16, 8.0, 0.3), 40, 24); }
// 60 pairs on a coarser hilly grid: the case that sees step 5 ruling out faces too eagerly
// (an exclusion at 0.8 U, found in review; at 0.98 U no mesh here fails).
TEST(TargetBoundStress, Hills) { stress("hills", test::hills(24, 6.0), 60, 28); }
TEST(TargetBoundStress, Holes) { stress("holes", grid_with_holes(16, 8.0, 0.6), 40, 1); }
TEST(TargetBoundStress, Rough) { stress("rough", rough_terrain(18, 6.0, 0.5, 3), 40, 2); }
TEST(TargetBoundStress, Needles) { stress("needles", needles(30, 6.0), 40, 3); }
TEST(TargetBoundStress, Monkey) { stress("monkey", monkey(20, 6.0, 2.5), 40, 4); }
TEST(TargetBoundStress, Spikes) { stress("spikes", spikes(20, 6.0), 40, 5); }
TEST(TargetBoundStress, Sphere) { stress("sphere", test::uv_sphere(1.0, 24, 12), 40, 6); }
TEST(TargetBoundStress, CoarseTorus) { stress("torus", test::torus(2.0, 0.7, 40, 8), 40, 7); }
TEST(TargetBoundStress, Octahedron) { stress("octahedron", test::octahedron(), 20, 8); }
TEST(TargetBoundStress, Tiny) {
  TriangleSoup s;
  s.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0.5)};
  s.triangles = {{0, 1, 2}, {1, 3, 2}};
  stress("tiny", s, 12, 9);
}
TEST(TargetBoundStress, TwoComponents) { stress("two comps", two_components(), 40, 10); }
TEST(TargetBoundStress, Cylinder) { stress("cylinder", test::open_cylinder(1.0, 3.0, 16, 6), 40, 11); }

}  // namespace
}  // namespace windplan
