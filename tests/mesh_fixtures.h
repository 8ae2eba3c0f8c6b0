#pragma once
// Meshes made in code, with known counts and closed-form geometry, for the core tests.
#include <array>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan::test {

/// A regular octahedron inscribed in the unit sphere: V=6, E=12, F=8, closed, genus 0.
inline TriangleSoup octahedron() {
  TriangleSoup s;
  s.points = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
              Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return s;
}

/// A planar grid of nx by ny squares of size h, each split into two triangles, in z = 0.
inline TriangleSoup grid(int nx, int ny, double h = 1.0) {
  TriangleSoup s;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) s.points.emplace_back(i * h, j * h, 0.0);
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

/// A torus (major radius R, minor radius r) with n by m quads: closed, genus 1, outward normals.
inline TriangleSoup torus(double R, double r, int n, int m) {
  TriangleSoup s;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = 2.0 * M_PI * i / n, v = 2.0 * M_PI * j / m;
      s.points.emplace_back((R + r * std::cos(v)) * std::cos(u),
                            (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [n, m](int i, int j) { return (j % m) * n + (i % n); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

/// A UV sphere of radius r with n segments around and m stacks, poles as single vertices.
inline TriangleSoup uv_sphere(double r, int n, int m) {
  TriangleSoup s;
  s.points.emplace_back(0, 0, -r);
  for (int j = 1; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const double th = M_PI * j / m - M_PI / 2, ph = 2.0 * M_PI * i / n;
      s.points.emplace_back(r * std::cos(th) * std::cos(ph), r * std::cos(th) * std::sin(ph),
                            r * std::sin(th));
    }
  s.points.emplace_back(0, 0, r);
  const int top = static_cast<int>(s.points.size()) - 1;
  auto id = [n](int i, int j) { return 1 + (j - 1) * n + (i % n); };
  for (int i = 0; i < n; ++i) s.triangles.push_back({0, id(i + 1, 1), id(i, 1)});
  for (int j = 1; j < m - 1; ++j)
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (int i = 0; i < n; ++i) s.triangles.push_back({id(i, m - 1), id(i + 1, m - 1), top});
  return s;
}

/// A surface of revolution about z: rings j = 0..m at z_j = z0 + (z1 - z0) j / m of radius
/// r(z_j), n vertices per ring at angles 2 pi i / n (the same on every ring), each quad split
/// along its diagonal (i, j)-(i + 1, j + 1); vertex (i, j) has index j n + i. An annulus with
/// outward normals.
inline TriangleSoup revolution(const std::function<double(double)>& r, double z0, double z1, int n,
                               int m) {
  TriangleSoup s;
  for (int j = 0; j <= m; ++j) {
    const double z = z0 + (z1 - z0) * j / m;
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * M_PI * i / n;
      s.points.emplace_back(r(z) * std::cos(t), r(z) * std::sin(t), z);
    }
  }
  auto id = [n](int i, int j) { return j * n + (i % n); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

/// The two boundary rings (vertex indices) of a revolution() / open_cylinder() mesh with n
/// vertices per ring and m + 1 rings.
inline std::array<std::vector<int>, 2> revolution_loops(int n, int m) {
  std::array<std::vector<int>, 2> loops;
  for (int i = 0; i < n; ++i) {
    loops[0].push_back(i);
    loops[1].push_back(m * n + i);
  }
  return loops;
}

/// An open cylinder (a tube without caps) of radius r and length len along z, with n vertices
/// around and m rings of quads along the axis (m + 1 vertex rings), each quad split in two.
/// Outward normals. Two boundary loops, genus 0, an annulus.
inline TriangleSoup open_cylinder(double r, double len, int n, int m) {
  return revolution([r](double) { return r; }, 0.0, len, n, m);
}

/// A torus with every vertex moved by up to `amplitude` (a fixed pseudo-random field): cone
/// angles on both sides of 2 pi everywhere, so windows of equal pseudo-source distance meet on
/// many edges.
inline TriangleSoup rough_torus(double amplitude, unsigned seed) {
  TriangleSoup s = torus(2.0, 0.7, 48, 20);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (Vec3& p : s.points) p += Vec3(u(rng), u(rng), u(rng));
  return s;
}

/// A grid with three Gaussian hills and a pit: saddle vertices on their flanks and pairs of
/// nearly equal geodesics on the two sides of each hill.
inline TriangleSoup hills(int n, double size) {
  TriangleSoup s = grid(n, n, size / n);
  const double cx[] = {0.35, 0.62, 0.5, 0.3}, cy[] = {0.4, 0.6, 0.25, 0.75};
  const double amp[] = {1.6, 1.2, 0.9, -0.8}, width[] = {0.12, 0.1, 0.08, 0.1};
  for (Vec3& p : s.points) {
    for (int k = 0; k < 4; ++k) {
      const double dx = p.x() / size - cx[k], dy = p.y() / size - cy[k];
      p.z() += amp[k] * std::exp(-(dx * dx + dy * dy) / (2.0 * width[k] * width[k]));
    }
  }
  return s;
}

/// The soup with its vertices and faces numbered at random and each face's corners rotated (the
/// same surface, as meshes written by remeshers often are numbered); perm[v] (optional) receives
/// the new index of vertex v.
inline TriangleSoup renumbered_at_random(const TriangleSoup& soup, unsigned seed,
                                         std::vector<int>* perm = nullptr) {
  std::mt19937 rng(seed);
  std::vector<int> vperm(soup.points.size()), fperm(soup.triangles.size());
  std::iota(vperm.begin(), vperm.end(), 0);
  std::iota(fperm.begin(), fperm.end(), 0);
  std::shuffle(vperm.begin(), vperm.end(), rng);
  std::shuffle(fperm.begin(), fperm.end(), rng);
  TriangleSoup out;
  out.points.resize(soup.points.size());
  for (std::size_t v = 0; v < vperm.size(); ++v) out.points[vperm[v]] = soup.points[v];
  for (const int f : fperm) {
    const Tri& t = soup.triangles[f];
    const int r = f % 3;
    out.triangles.push_back({vperm[t[r]], vperm[t[(r + 1) % 3]], vperm[t[(r + 2) % 3]]});
  }
  if (perm != nullptr) *perm = std::move(vperm);
  return out;
}

}  // namespace windplan::test
