// Over 800 lines, kept in one file on purpose: check_mesh and repair_mesh share one analysis of the
// soup (analyze(): edge manifoldness, orientation, components, boundaries), and each repair step
// re-runs it; split, the analysis would need a header of its own for two callers.
#include "geometry/mesh/mesh_validation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh_io.h"

namespace windplan {

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

bool valid_tri(const Tri& t, int nv) {
  return t[0] >= 0 && t[0] < nv && t[1] >= 0 && t[1] < nv && t[2] >= 0 && t[2] < nv;
}
bool degenerate_tri(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// Everything check_mesh and repair_mesh need: edge groups over the halfedges of the usable
// (valid, non-degenerate) triangles, and the fan id of every corner.
struct Analysis {
  MeshHealth health;
  std::vector<char> usable;  // per triangle
  // Halfedges h = 3f + k of usable triangles, sorted by undirected edge; groups are runs.
  std::vector<std::pair<std::uint64_t, int>> halfedges;
  std::vector<int> group_start;     // group g is halfedges[group_start[g], group_start[g+1])
  std::vector<int> group_of;        // per halfedge 3f+k (-1 for unusable triangles)
  std::vector<int> corner_fan;      // per corner 3f+k: representative corner of its fan
  std::vector<int> face_component;  // per triangle (-1 for unusable)
};

std::string pair_str(const std::array<int, 2>& e) {
  return "(" + std::to_string(e[0]) + ", " + std::to_string(e[1]) + ")";
}

template <class T, class F>
std::string list_str(const std::vector<T>& v, int total, F fmt, std::size_t max_items = 5) {
  std::string s;
  for (std::size_t i = 0; i < v.size() && i < max_items; ++i) s += (i ? ", " : "") + fmt(v[i]);
  if (total > static_cast<int>(std::min(v.size(), max_items))) s += ", ...";
  return s;
}

Analysis analyze(const TriangleSoup& soup, const MeshCheckOptions& opt) {
  Analysis a;
  MeshHealth& h = a.health;
  const int nv = static_cast<int>(soup.points.size());
  const int nf = static_cast<int>(soup.triangles.size());
  const std::size_t max_listed = static_cast<std::size_t>(std::max(0, opt.max_listed));
  h.num_vertices = nv;
  h.num_faces = nf;

  // Triangle classes and referenced vertices.
  a.usable.assign(nf, 0);
  std::vector<char> referenced(nv, 0);
  for (int f = 0; f < nf; ++f) {
    const Tri& t = soup.triangles[f];
    if (!valid_tri(t, nv)) {
      ++h.num_invalid_triangles;
      continue;
    }
    for (int k = 0; k < 3; ++k) referenced[t[k]] = 1;
    if (degenerate_tri(t)) {
      ++h.num_degenerate_triangles;
      if (h.degenerate_triangles.size() < max_listed) h.degenerate_triangles.push_back(f);
      continue;
    }
    a.usable[f] = 1;
  }
  h.num_referenced_vertices = static_cast<int>(std::count(referenced.begin(), referenced.end(), 1));
  h.num_unreferenced_vertices = nv - h.num_referenced_vertices;

  // Bounding box of the referenced vertices (all of them when none is referenced).
  bool first = true;
  for (int v = 0; v < nv; ++v) {
    if (!referenced[v] && h.num_referenced_vertices > 0) continue;
    const Vec3& p = soup.points[v];
    if (first) {
      h.bbox.min = h.bbox.max = p;
      first = false;
    } else {
      h.bbox.min = h.bbox.min.cwiseMin(p);
      h.bbox.max = h.bbox.max.cwiseMax(p);
    }
  }
  const double diag = h.bbox.diagonal_length();
  const double area_tol = opt.zero_area_tolerance * diag * diag;

  // Exactly duplicate points.
  {
    std::vector<int> order(nv);
    std::iota(order.begin(), order.end(), 0);
    auto less = [&](int i, int j) {
      const Vec3 &p = soup.points[i], &q = soup.points[j];
      if (p.x() != q.x()) return p.x() < q.x();
      if (p.y() != q.y()) return p.y() < q.y();
      return p.z() < q.z();
    };
    std::sort(order.begin(), order.end(), less);
    for (int i = 1; i < nv; ++i) {
      if (soup.points[order[i]] == soup.points[order[i - 1]]) ++h.num_duplicate_vertices;
    }
  }

  // Zero-area and duplicate triangles (sorted vertex triples, bucketed by the smallest vertex).
  {
    std::vector<int> start(static_cast<std::size_t>(nv) + 1, 0);
    for (int f = 0; f < nf; ++f) {
      if (!a.usable[f]) continue;
      const Tri& t = soup.triangles[f];
      const Vec3& p0 = soup.points[t[0]];
      const double area = 0.5 * (soup.points[t[1]] - p0).cross(soup.points[t[2]] - p0).norm();
      if (area <= area_tol) {
        ++h.num_zero_area_triangles;
        if (h.zero_area_triangles.size() < max_listed) h.zero_area_triangles.push_back(f);
      }
      ++start[std::min({t[0], t[1], t[2]}) + 1];
    }
    for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<std::uint64_t> rest(start[nv]);  // (mid << 32 | max) per bucket
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int f = 0; f < nf; ++f) {
      if (!a.usable[f]) continue;
      std::array<int, 3> t = soup.triangles[f];
      std::sort(t.begin(), t.end());
      rest[fill[t[0]]++] = edge_key(t[1], t[2]);
    }
    for (int v = 0; v < nv; ++v) {
      std::sort(rest.begin() + start[v], rest.begin() + start[v + 1]);
      for (int i = start[v] + 1; i < start[v + 1]; ++i) {
        if (rest[i] == rest[i - 1]) ++h.num_duplicate_triangles;
      }
    }
  }

  // Edge groups: halfedges bucketed by their smaller vertex (counting sort), each bucket then
  // sorted by the larger one. Linear for bounded degree; a global sort costs 3x more at 300k faces.
  {
    std::vector<int> start(static_cast<std::size_t>(nv) + 1, 0);
    for (int f = 0; f < nf; ++f) {
      if (!a.usable[f]) continue;
      const Tri& t = soup.triangles[f];
      for (int k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
    }
    for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
    a.halfedges.resize(start[nv]);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int f = 0; f < nf; ++f) {
      if (!a.usable[f]) continue;
      const Tri& t = soup.triangles[f];
      for (int k = 0; k < 3; ++k) {
        a.halfedges[fill[std::min(t[k], t[(k + 1) % 3])]++] = {edge_key(t[k], t[(k + 1) % 3]),
                                                               3 * f + k};
      }
    }
    for (int v = 0; v < nv; ++v) {
      auto b = a.halfedges.begin() + start[v], e = a.halfedges.begin() + start[v + 1];
      // Insertion sort for the usual few edges; std::sort for high-valence vertices (fan apexes).
      if (e - b > 32) {
        std::sort(b, e);
        continue;
      }
      for (auto i = b; i != e; ++i)
        for (auto j = i; j != b && *j < *(j - 1); --j) std::iter_swap(j, j - 1);
    }
  }
  a.group_of.assign(3 * static_cast<std::size_t>(nf), -1);
  for (std::size_t i = 0; i < a.halfedges.size(); ++i) {
    if (i == 0 || a.halfedges[i].first != a.halfedges[i - 1].first) {
      a.group_start.push_back(static_cast<int>(i));
    }
    a.group_of[a.halfedges[i].second] = static_cast<int>(a.group_start.size()) - 1;
  }
  const int ng = static_cast<int>(a.group_start.size());
  a.group_start.push_back(static_cast<int>(a.halfedges.size()));
  h.num_edges = ng;

  UnionFind faces(nf);
  UnionFind corners(3 * nf);
  UnionFind boundary(nv);
  std::vector<char> on_boundary(nv, 0);
  double len_sum = 0.0;
  h.min_edge_length = ng > 0 ? std::numeric_limits<double>::infinity() : 0.0;
  auto from = [&](int he) { return soup.triangles[he / 3][he % 3]; };
  auto to = [&](int he) { return soup.triangles[he / 3][(he % 3 + 1) % 3]; };
  for (int g = 0; g < ng; ++g) {
    const int b = a.group_start[g], e = a.group_start[g + 1], n = e - b;
    const int h0 = a.halfedges[b].second;
    const int u = std::min(from(h0), to(h0)), w = std::max(from(h0), to(h0));
    const double len = (soup.points[u] - soup.points[w]).norm();
    len_sum += len;
    h.min_edge_length = std::min(h.min_edge_length, len);
    h.max_edge_length = std::max(h.max_edge_length, len);
    if (n == 1) {
      ++h.num_boundary_edges;
      boundary.unite(u, w);
      on_boundary[u] = on_boundary[w] = 1;
    } else if (n > 2) {
      ++h.num_nonmanifold_edges;
      if (h.nonmanifold_edges.size() < max_listed) h.nonmanifold_edges.push_back({u, w});
    } else if (from(h0) == from(a.halfedges[b + 1].second)) {
      ++h.num_inconsistent_edges;
      if (h.inconsistent_edges.size() < max_listed) h.inconsistent_edges.push_back({u, w});
    }
    // Link the triangles (components) and the corners at both ends (fans).
    for (int i = b + 1; i < e; ++i) {
      const int hi = a.halfedges[i].second;
      faces.unite(h0 / 3, hi / 3);
    }
    for (int i = b; i < e; ++i) {
      const int hi = a.halfedges[i].second;
      const int fi = hi / 3;
      // Corner of u and of w in triangle fi.
      for (int k = 0; k < 3; ++k) {
        const int c = 3 * fi + k;
        const int v = soup.triangles[fi][k];
        if (v == u) corners.unite(c, 3 * (h0 / 3) + (from(h0) == u ? h0 % 3 : (h0 % 3 + 1) % 3));
        if (v == w) corners.unite(c, 3 * (h0 / 3) + (from(h0) == w ? h0 % 3 : (h0 % 3 + 1) % 3));
      }
    }
  }
  h.mean_edge_length = ng > 0 ? len_sum / ng : 0.0;

  // Fans per vertex: count root corners per vertex.
  a.corner_fan.assign(3 * static_cast<std::size_t>(nf), -1);
  std::vector<int> fans(nv, 0);
  for (int f = 0; f < nf; ++f) {
    if (!a.usable[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const int c = 3 * f + k;
      a.corner_fan[c] = corners.find(c);
      if (a.corner_fan[c] == c) ++fans[soup.triangles[f][k]];
    }
  }
  for (int v = 0; v < nv; ++v) {
    if (fans[v] > 1) {
      ++h.num_nonmanifold_vertices;
      if (h.nonmanifold_vertices.size() < max_listed) h.nonmanifold_vertices.push_back(v);
    }
  }

  // Components and boundary loops.
  a.face_component.assign(nf, -1);
  {
    std::vector<int> id(nf, -1);
    for (int f = 0; f < nf; ++f) {
      if (!a.usable[f]) continue;
      const int r = faces.find(f);
      if (id[r] < 0) id[r] = h.num_components++;
      a.face_component[f] = id[r];
    }
  }
  for (int v = 0; v < nv; ++v) {
    if (on_boundary[v] && boundary.find(v) == v) ++h.num_boundary_loops;
  }

  int usable_faces = 0;
  std::vector<char> used(nv, 0);
  for (int f = 0; f < nf; ++f) {
    if (!a.usable[f]) continue;
    ++usable_faces;
    for (int k = 0; k < 3; ++k) used[soup.triangles[f][k]] = 1;
  }
  const int used_vertices = static_cast<int>(std::count(used.begin(), used.end(), 1));
  h.euler_characteristic = used_vertices - h.num_edges + usable_faces;
  h.closed = h.num_boundary_edges == 0;
  h.manifold = h.num_nonmanifold_edges == 0 && h.num_nonmanifold_vertices == 0;
  h.oriented = h.num_inconsistent_edges == 0;
  if (h.manifold && h.num_components == 1) {
    h.genus = (2 - h.euler_characteristic - h.num_boundary_loops) / 2;
  }
  return a;
}

// Re-index vertices so that only referenced ones remain, in their original order.
int drop_unreferenced(TriangleSoup* soup) {
  std::vector<int> remap(soup->points.size(), -1);
  for (const Tri& t : soup->triangles)
    for (int v : t) remap[v] = 0;
  int n = 0;
  std::vector<Vec3> pts;
  pts.reserve(soup->points.size());
  for (std::size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] < 0) continue;
    remap[v] = n++;
    pts.push_back(soup->points[v]);
  }
  const int removed = static_cast<int>(soup->points.size()) - n;
  for (Tri& t : soup->triangles)
    for (int& v : t) v = remap[v];
  soup->points = std::move(pts);
  return removed;
}

std::string plural(int n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// Removes zero-area "cap" triangles (a, b, c) with c on the segment ab by flipping the edge ab:
// with the neighbour (b, a, d), the pair becomes (a, d, c) and (d, b, c), which cover exactly the
// same surface. Returns the number removed; the others are left alone.
int flip_zero_area(TriangleSoup* soup, double area_tol, std::vector<int>* left) {
  auto area = [&](const Tri& t) {
    const Vec3& p0 = soup->points[t[0]];
    return 0.5 * (soup->points[t[1]] - p0).cross(soup->points[t[2]] - p0).norm();
  };
  std::vector<int> bad;
  for (int f = 0; f < static_cast<int>(soup->triangles.size()); ++f) {
    if (area(soup->triangles[f]) <= area_tol) bad.push_back(f);
  }
  if (bad.empty()) return 0;
  // Directed edge -> triangle (the soup is manifold and oriented here).
  std::unordered_map<std::uint64_t, int> directed;
  auto dkey = [](int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
  };
  auto index_tri = [&](int f, bool add) {
    const Tri& t = soup->triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (add)
        directed[dkey(t[k], t[(k + 1) % 3])] = f;
      else
        directed.erase(dkey(t[k], t[(k + 1) % 3]));
    }
  };
  for (int f = 0; f < static_cast<int>(soup->triangles.size()); ++f) index_tri(f, true);
  int removed = 0;
  for (int f : bad) {
    const Tri t = soup->triangles[f];
    // The longest edge (a, b) and the opposite corner c.
    int k = 0;
    double best = -1.0;
    for (int j = 0; j < 3; ++j) {
      const double l = (soup->points[t[(j + 1) % 3]] - soup->points[t[j]]).squaredNorm();
      if (l > best) {
        best = l;
        k = j;
      }
    }
    const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
    const Vec3 ab = soup->points[b] - soup->points[a];
    const double s =
        ab.squaredNorm() > 0 ? (soup->points[c] - soup->points[a]).dot(ab) / ab.squaredNorm() : -1;
    const auto it = directed.find(dkey(b, a));
    bool ok = s > 0.0 && s < 1.0 && it != directed.end();
    int g = -1, d = -1;
    if (ok) {
      g = it->second;
      const Tri& u = soup->triangles[g];
      for (int j = 0; j < 3; ++j)
        if (u[j] != a && u[j] != b) d = u[j];
      ok = d >= 0 && d != c && directed.count(dkey(c, d)) == 0 && directed.count(dkey(d, c)) == 0;
    }
    if (ok) {
      const Tri n1 = {a, d, c}, n2 = {d, b, c};
      ok = area(n1) > area_tol && area(n2) > area_tol;
      if (ok) {
        index_tri(f, false);
        index_tri(g, false);
        soup->triangles[f] = n1;
        soup->triangles[g] = n2;
        index_tri(f, true);
        index_tri(g, true);
        ++removed;
      }
    }
    if (!ok) left->push_back(f);
  }
  return removed;
}

}  // namespace

bool MeshCheckOptions::is_valid(std::string* why) const {
  if (!(zero_area_tolerance >= 0.0) || !std::isfinite(zero_area_tolerance)) {
    if (why) *why = "zero_area_tolerance must be a finite number >= 0";
    return false;
  }
  if (max_listed < 0) {
    if (why) *why = "max_listed must be >= 0";
    return false;
  }
  return true;
}

bool RepairOptions::is_valid(std::string* why) const { return check.is_valid(why); }

std::vector<std::string> MeshHealth::blocking_problems() const {
  std::vector<std::string> p;
  auto edges = [](const std::vector<std::array<int, 2>>& v, int n) {
    return list_str(v, n, pair_str);
  };
  auto ints = [](const std::vector<int>& v, int n) {
    return list_str(v, n, [](int i) { return std::to_string(i); });
  };
  if (num_invalid_triangles > 0) {
    p.push_back(plural(num_invalid_triangles, "triangle has", "triangles have") +
                " a vertex index out of range");
  }
  if (num_nonmanifold_edges > 0) {
    p.push_back(
        plural(num_nonmanifold_edges, "non-manifold edge", "non-manifold edges") +
        " (in more than two triangles): " + edges(nonmanifold_edges, num_nonmanifold_edges));
  }
  if (num_nonmanifold_vertices > 0) {
    p.push_back(plural(num_nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices") +
                " (more than one fan): " + ints(nonmanifold_vertices, num_nonmanifold_vertices));
  }
  if (num_inconsistent_edges > 0) {
    p.push_back(plural(num_inconsistent_edges, "edge is", "edges are") +
                " traversed twice in the same direction (inconsistent orientation): " +
                edges(inconsistent_edges, num_inconsistent_edges));
  }
  if (num_degenerate_triangles > 0) {
    p.push_back(
        plural(num_degenerate_triangles, "degenerate triangle", "degenerate triangles") +
        " (repeated vertex index): " + ints(degenerate_triangles, num_degenerate_triangles));
  }
  return p;
}

std::vector<std::string> MeshHealth::problems() const {
  std::vector<std::string> p = blocking_problems();
  auto ints = [](const std::vector<int>& v, int n) {
    return list_str(v, n, [](int i) { return std::to_string(i); });
  };
  if (num_zero_area_triangles > 0) {
    p.push_back(plural(num_zero_area_triangles, "zero-area triangle", "zero-area triangles") +
                ": " + ints(zero_area_triangles, num_zero_area_triangles));
  }
  if (num_duplicate_triangles > 0) {
    p.push_back(plural(num_duplicate_triangles, "duplicate triangle", "duplicate triangles"));
  }
  if (num_duplicate_vertices > 0) {
    p.push_back(plural(num_duplicate_vertices, "vertex duplicates", "vertices duplicate") +
                " the exact position of another");
  }
  if (num_unreferenced_vertices > 0) {
    p.push_back(plural(num_unreferenced_vertices, "unreferenced vertex", "unreferenced vertices"));
  }
  if (num_boundary_edges > 0) {
    p.push_back("open: " + plural(num_boundary_edges, "boundary edge", "boundary edges") + " in " +
                plural(num_boundary_loops, "loop", "loops"));
  }
  return p;
}

std::string MeshHealth::brief_report() const {
  std::ostringstream s;
  s.precision(6);
  s << "vertices:        " << num_vertices;
  if (num_unreferenced_vertices > 0) s << " (" << num_unreferenced_vertices << " unreferenced)";
  s << "\nfaces:           " << num_faces << "\nedges:           " << num_edges
    << "\ncomponents:      " << num_components << "\nboundary loops:  " << num_boundary_loops
    << " (" << num_boundary_edges << " boundary edges)"
    << "\neuler char.:     " << euler_characteristic
    << "\ngenus:           " << (genus >= 0 ? std::to_string(genus) : std::string("n/a"))
    << "\nclosed:          " << (closed ? "yes" : "no")
    << "\nmanifold:        " << (manifold ? "yes" : "no")
    << "\noriented:        " << (oriented ? "yes" : "no") << "\nbbox min:        (" << bbox.min.x()
    << ", " << bbox.min.y() << ", " << bbox.min.z() << ")"
    << "\nbbox max:        (" << bbox.max.x() << ", " << bbox.max.y() << ", " << bbox.max.z()
    << ")\nedge length:     min " << min_edge_length << ", mean " << mean_edge_length << ", max "
    << max_edge_length << "\ndegenerate:      " << num_degenerate_triangles << " repeated-index, "
    << num_zero_area_triangles << " zero-area\n";
  return s.str();
}

MeshHealth check_mesh(const TriangleSoup& soup, const MeshCheckOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("mesh check options: " + why);
  return analyze(soup, options).health;
}

RepairResult repair_mesh(TriangleSoup soup, const RepairOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("repair options: " + why);
  RepairResult r;
  Analysis a = analyze(soup, options.check);
  r.before = a.health;
  const int nv0 = static_cast<int>(soup.points.size());

  // 1. Triangles with an index out of range cannot be repaired: drop them.
  if (a.health.num_invalid_triangles > 0) {
    std::vector<Tri> keep;
    for (const Tri& t : soup.triangles)
      if (valid_tri(t, nv0)) keep.push_back(t);
    soup.triangles = std::move(keep);
    r.changes.push_back("dropped " +
                        plural(a.health.num_invalid_triangles, "triangle", "triangles") +
                        " with a vertex index out of range");
    a = analyze(soup, options.check);
  }

  // 2. Merge exactly duplicate vertices, unless that creates non-manifold edges or vertices
  //    (e.g. a lid whose rim touches the body at identical points must stay separate).
  if (a.health.num_duplicate_vertices > 0) {
    TriangleSoup merged = weld_vertices(soup, 0.0);
    const int n = static_cast<int>(soup.points.size() - merged.points.size());
    Analysis b = analyze(merged, options.check);
    if (b.health.num_nonmanifold_edges <= a.health.num_nonmanifold_edges &&
        b.health.num_nonmanifold_vertices <= a.health.num_nonmanifold_vertices) {
      soup = std::move(merged);
      a = std::move(b);
      r.merged_vertices = n;
      r.changes.push_back("merged " + plural(n, "vertex", "vertices") +
                          " at exactly the same position as another");
    } else {
      r.kept.push_back("kept " + plural(n, "duplicate vertex", "duplicate vertices") +
                       ": merging them would create non-manifold edges or vertices");
    }
  }

  // 3. Degenerate (repeated index) and duplicate triangles.
  if (a.health.num_degenerate_triangles + a.health.num_duplicate_triangles > 0) {
    std::vector<Tri> keep;
    keep.reserve(soup.triangles.size());
    std::vector<std::pair<std::array<int, 3>, int>> sorted;
    int degenerate = 0;
    for (const Tri& t : soup.triangles) {
      if (degenerate_tri(t)) {
        ++degenerate;
        continue;
      }
      std::array<int, 3> s = t;
      std::sort(s.begin(), s.end());
      sorted.push_back({s, static_cast<int>(keep.size())});
      keep.push_back(t);
    }
    std::sort(sorted.begin(), sorted.end());
    std::vector<char> dup(keep.size(), 0);
    int duplicates = 0;
    for (std::size_t i = 1; i < sorted.size(); ++i) {
      if (sorted[i].first == sorted[i - 1].first) {
        dup[sorted[i].second] = 1;  // the later copy (pairs sort by index within equal keys)
        ++duplicates;
      }
    }
    if (degenerate + duplicates > 0) {
      std::vector<Tri> out;
      out.reserve(keep.size());
      for (std::size_t i = 0; i < keep.size(); ++i)
        if (!dup[i]) out.push_back(keep[i]);
      soup.triangles = std::move(out);
      if (degenerate > 0) {
        r.removed_degenerate = degenerate;
        r.changes.push_back("dropped " +
                            plural(degenerate, "degenerate triangle", "degenerate triangles") +
                            " (repeated vertex index)");
      }
      if (duplicates > 0) {
        r.removed_duplicates = duplicates;
        r.changes.push_back("dropped " +
                            plural(duplicates, "duplicate triangle", "duplicate triangles") +
                            " (same three vertices as an earlier one)");
      }
      a = analyze(soup, options.check);
    }
  }

  // 4. What cannot be repaired safely.
  const MeshHealth& h = a.health;
  if (h.num_nonmanifold_edges > 0) {
    throw TopologyError("cannot repair " +
                        plural(h.num_nonmanifold_edges, "non-manifold edge", "non-manifold edges") +
                        " (shared by more than two triangles): " +
                        list_str(h.nonmanifold_edges, h.num_nonmanifold_edges, pair_str));
  }
  if (h.num_nonmanifold_vertices > 0) {
    if (!options.split_nonmanifold_vertices) {
      throw TopologyError(
          "cannot repair " +
          plural(h.num_nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices") +
          " (triangles forming more than one fan): " +
          list_str(h.nonmanifold_vertices, h.num_nonmanifold_vertices,
                   [](int i) { return std::to_string(i); }) +
          " (splitting them per fan is an option)");
    }
    // Keep the first fan on the vertex; every other fan gets a copy of the vertex.
    const int nf = static_cast<int>(soup.triangles.size());
    std::unordered_map<int, int> fan_vertex;  // representative corner -> vertex
    std::vector<char> has_fan(soup.points.size(), 0);
    int added = 0;
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        const int c = 3 * f + k;
        const int rep = a.corner_fan[c];
        if (rep < 0) continue;
        int& v = soup.triangles[f][k];
        auto it = fan_vertex.find(rep);
        if (it == fan_vertex.end()) {
          if (!has_fan[v]) {
            has_fan[v] = 1;
            fan_vertex.emplace(rep, v);
          } else {
            const int nvtx = static_cast<int>(soup.points.size());
            soup.points.push_back(soup.points[v]);
            has_fan.push_back(1);
            fan_vertex.emplace(rep, nvtx);
            v = nvtx;
            ++added;
          }
        } else {
          v = it->second;
        }
      }
    }
    r.split_vertices = added;
    r.changes.push_back(
        "split " +
        plural(h.num_nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices") +
        " into one vertex per fan (" + plural(added, "vertex", "vertices") + " added)");
  }

  // 5. Unreferenced vertices.
  {
    const int removed = drop_unreferenced(&soup);
    if (removed > 0) {
      r.removed_unreferenced = removed;
      r.changes.push_back("dropped " +
                          plural(removed, "unreferenced vertex", "unreferenced vertices"));
    }
    if (removed > 0 || r.split_vertices > 0) a = analyze(soup, options.check);
  }

  // 6. Consistent orientation per component (BFS across manifold edges), keeping the majority.
  const int nf = static_cast<int>(soup.triangles.size());
  std::vector<char> flip(nf, 0), seen(nf, 0);
  int flipped_consistency = 0, flipped_outward = 0, outward_components = 0;
  std::vector<std::vector<int>> comp_faces(a.health.num_components);
  for (int f = 0; f < nf; ++f) comp_faces[a.face_component[f]].push_back(f);
  for (int c = 0; c < a.health.num_components; ++c) {
    const std::vector<int>& faces = comp_faces[c];
    std::vector<int> queue = {faces[0]};
    seen[faces[0]] = 1;
    for (std::size_t qi = 0; qi < queue.size(); ++qi) {
      const int f = queue[qi];
      for (int k = 0; k < 3; ++k) {
        const int he = 3 * f + k;
        const int g = a.group_of[he];
        const int b = a.group_start[g], e = a.group_start[g + 1];
        if (e - b != 2) continue;
        const int other =
            a.halfedges[b].second == he ? a.halfedges[b + 1].second : a.halfedges[b].second;
        const int fo = other / 3;
        // Same direction in the file <=> the two need opposite flip states.
        const bool same_dir = soup.triangles[f][k] == soup.triangles[fo][other % 3];
        const char want = same_dir ? !flip[f] : flip[f];
        if (!seen[fo]) {
          seen[fo] = 1;
          flip[fo] = want;
          queue.push_back(fo);
        } else if (flip[fo] != want) {
          throw TopologyError(
              "cannot orient component " + std::to_string(c) + " (the one containing triangle " +
              std::to_string(faces[0]) +
              "): it is non-orientable (a Moebius-like surface); conflict at edge " +
              pair_str({std::min(soup.triangles[f][k], soup.triangles[f][(k + 1) % 3]),
                        std::max(soup.triangles[f][k], soup.triangles[f][(k + 1) % 3])}));
        }
      }
    }
    int nflip = 0;
    for (int f : faces) nflip += flip[f];
    if (2 * nflip > static_cast<int>(faces.size())) {
      for (int f : faces) flip[f] = !flip[f];
      nflip = static_cast<int>(faces.size()) - nflip;
    }
    flipped_consistency += nflip;
    // Outward normals for closed components: the signed volume must be positive.
    bool closed = true;
    for (int f : faces)
      for (int k = 0; k < 3; ++k) {
        const int g = a.group_of[3 * f + k];
        closed = closed && a.group_start[g + 1] - a.group_start[g] == 2;
      }
    if (closed && options.orient_outward) {
      double vol = 0.0;
      for (int f : faces) {
        Tri t = soup.triangles[f];
        if (flip[f]) std::swap(t[1], t[2]);
        vol += soup.points[t[0]].dot(soup.points[t[1]].cross(soup.points[t[2]])) / 6.0;
      }
      if (vol < 0.0) {
        for (int f : faces) flip[f] = !flip[f];
        ++outward_components;
        flipped_outward += static_cast<int>(faces.size());
      }
    }
  }
  int total_flips = 0;
  for (int f = 0; f < nf; ++f) {
    if (!flip[f]) continue;
    std::swap(soup.triangles[f][1], soup.triangles[f][2]);
    ++total_flips;
  }
  r.flipped_triangles = total_flips;
  if (flipped_consistency > 0) {
    r.changes.push_back("re-oriented " + plural(flipped_consistency, "triangle", "triangles") +
                        " so that every edge is traversed once in each direction");
  }
  if (outward_components > 0) {
    r.changes.push_back("turned " +
                        plural(outward_components, "closed component", "closed components") + " (" +
                        plural(flipped_outward, "triangle", "triangles") +
                        ") inside out so that the normals point outward");
  }

  // 7. Zero-area cap triangles: an edge flip removes them without changing the surface.
  if (a.health.num_zero_area_triangles > 0) {
    const double diag = a.health.bbox.diagonal_length();
    std::vector<int> left;
    const int removed =
        flip_zero_area(&soup, options.check.zero_area_tolerance * diag * diag, &left);
    if (removed > 0) {
      r.removed_zero_area = removed;
      r.changes.push_back("removed " +
                          plural(removed, "zero-area triangle", "zero-area triangles") +
                          " by flipping its long edge (the surface is unchanged)");
    }
    // What cannot be flipped may still be dropped when it lies on the open boundary: that opens
    // no new hole and loses no area. Accepted only if the result stays an oriented manifold with
    // the same number of components.
    if (!left.empty()) {
      const Analysis now = analyze(soup, options.check);
      std::vector<char> drop(soup.triangles.size(), 0);
      std::vector<int> still;
      int ndrop = 0;
      for (int f : left) {
        bool on_boundary = false;
        for (int k = 0; k < 3; ++k) {
          const int g = now.group_of[3 * f + k];
          on_boundary = on_boundary || (g >= 0 && now.group_start[g + 1] - now.group_start[g] == 1);
        }
        if (on_boundary) {
          drop[f] = 1;
          ++ndrop;
        } else {
          still.push_back(f);
        }
      }
      if (ndrop > 0) {
        TriangleSoup candidate;
        candidate.points = soup.points;
        for (std::size_t f = 0; f < soup.triangles.size(); ++f)
          if (!drop[f]) candidate.triangles.push_back(soup.triangles[f]);
        const int unreferenced = drop_unreferenced(&candidate);
        const MeshHealth ch = analyze(candidate, options.check).health;
        if (ch.manifold && ch.oriented && ch.num_components == now.health.num_components) {
          soup = std::move(candidate);
          r.removed_zero_area += ndrop;
          r.removed_unreferenced += unreferenced;
          r.changes.push_back(
              "dropped " + plural(ndrop, "zero-area triangle", "zero-area triangles") +
              " on the open boundary (no area lost, no new hole)" +
              (unreferenced > 0
                   ? " and the " + plural(unreferenced, "vertex", "vertices") + " only they used"
                   : std::string()));
          left = std::move(still);
        }
      }
    }
    if (!left.empty()) {
      r.kept.push_back(
          "kept " +
          plural(static_cast<int>(left.size()), "zero-area triangle", "zero-area triangles") +
          " (no safe edge flip, not droppable without opening a hole): " +
          list_str(left, static_cast<int>(left.size()), [](int i) { return std::to_string(i); }));
    }
  }

  r.after = r.changes.empty() ? r.before : check_mesh(soup, options.check);
  r.soup = std::move(soup);
  return r;
}

Mesh build_mesh(TriangleSoup soup, bool repair, MeshHealth* health_out,
                std::vector<std::string>* changes, const RepairOptions& options) {
  if (!repair) {
    const MeshHealth h = check_mesh(soup, options.check);
    if (health_out) *health_out = h;
    if (!h.is_valid_mesh()) {
      std::string msg;
      for (const std::string& p : h.blocking_problems()) msg += (msg.empty() ? "" : "; ") + p;
      throw TopologyError("the mesh is not a valid oriented 2-manifold: " + msg +
                          " (repair: true fixes orientation and degenerate triangles)");
    }
    return Mesh(std::move(soup));
  }
  RepairResult r = repair_mesh(std::move(soup), options);
  if (health_out) *health_out = r.before;
  if (changes) changes->insert(changes->end(), r.changes.begin(), r.changes.end());
  return Mesh(std::move(r.soup));
}

}  // namespace windplan
