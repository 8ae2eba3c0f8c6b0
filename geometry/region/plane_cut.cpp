#include "geometry/region/plane_cut.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "geometry/base/errors.h"

namespace windplan {

bool PlaneCutOptions::is_valid(std::string* why) const {
  if (!(min_fraction >= 0.0 && min_fraction < 0.5)) {
    if (why) *why = "plane cut min_fraction must be in [0, 0.5)";
    return false;
  }
  return true;
}

namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

int sign_of(double d) { return d > 0.0 ? 1 : (d < 0.0 ? -1 : 0); }

}  // namespace

PlaneCutResult cut_at_stations(const Mesh& mesh, const SpindleAxis& axis_in,
                               const std::vector<double>& stations,
                               const PlaneCutOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError(why);
  SpindleAxis axis = axis_in;
  axis.direction.normalize();
  const Vec3& dir = axis.direction;
  PlaneCutResult out;
  std::vector<Vec3> pts = mesh.points();
  std::vector<Tri> tris = mesh.triangles();
  std::vector<int> fparent(tris.size());
  for (std::size_t f = 0; f < tris.size(); ++f) fparent[f] = static_cast<int>(f);
  std::vector<int> vparent(pts.size());
  for (std::size_t v = 0; v < pts.size(); ++v) vparent[v] = static_cast<int>(v);
  const double scale = std::max(1.0, mesh.bounding_box().diagonal_length());
  const double on_plane = 1e-12 * scale;
  const double f_min = options.min_fraction;
  std::vector<char> split_face(tris.size(), 0);

  for (const double s : stations) {
    // Exact placement: move p along the axis so that its axial coordinate is s.
    auto onto = [&](Vec3 p) {
      p -= (axis.axial(p) - s) * dir;
      return p;
    };
    std::vector<double> d(pts.size());
    for (std::size_t v = 0; v < pts.size(); ++v) {
      d[v] = axis.axial(pts[v]) - s;
      if (std::abs(d[v]) <= on_plane && d[v] != 0.0) {
        pts[v] = onto(pts[v]);
        d[v] = 0.0;
      }
    }
    // No-sliver rule: a crossing closer to a vertex than min_fraction of the vertex's shortest
    // edge moves the vertex there (a move that small cannot fold its triangles); otherwise the
    // edge is split and the new vertex keeps that distance from it.
    std::vector<double> shortest(pts.size(), std::numeric_limits<double>::infinity());
    for (const Tri& t : tris) {
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        const double l = (pts[a] - pts[b]).norm();
        shortest[a] = std::min(shortest[a], l);
        shortest[b] = std::min(shortest[b], l);
      }
    }
    std::vector<double> best_move(pts.size(), -1.0);
    std::vector<Vec3> target(pts.size());
    for (const Tri& t : tris) {
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        if (!(d[a] * d[b] < 0.0)) continue;
        const double u = d[a] / (d[a] - d[b]);
        const Vec3 x = onto(pts[a] + u * (pts[b] - pts[a]));
        for (const int v : {a, b}) {
          const double move = (x - pts[v]).norm();
          if (move < f_min * shortest[v] && (best_move[v] < 0.0 || move < best_move[v])) {
            best_move[v] = move;
            target[v] = x;
          }
        }
      }
    }
    for (std::size_t v = 0; v < pts.size(); ++v) {
      if (best_move[v] < 0.0) continue;
      pts[v] = target[v];
      d[v] = 0.0;
      ++out.moved_vertices;
      out.max_move = std::max(out.max_move, best_move[v]);
    }
    // Split the remaining crossings: one new vertex per edge, shared by both of its triangles.
    std::unordered_map<std::uint64_t, int> cut_vertex;
    auto crossing = [&](int a, int b) {
      const auto [it, fresh] = cut_vertex.try_emplace(edge_key(a, b), -1);
      if (fresh) {
        const double u = d[a] / (d[a] - d[b]);
        it->second = static_cast<int>(pts.size());
        pts.push_back(onto(pts[a] + u * (pts[b] - pts[a])));
        d.push_back(0.0);
        vparent.push_back(-1);
        ++out.split_edges;
      }
      return it->second;
    };
    std::vector<Tri> next;
    std::vector<int> next_parent;
    next.reserve(tris.size() + tris.size() / 8);
    next_parent.reserve(next.capacity());
    auto emit = [&](int a, int b, int c, int parent) {
      next.push_back(Tri{a, b, c});
      next_parent.push_back(parent);
    };
    for (std::size_t f = 0; f < tris.size(); ++f) {
      const Tri& t = tris[f];
      const int p = fparent[f];
      int sg[3];
      for (int k = 0; k < 3; ++k) sg[k] = sign_of(d[t[k]]);
      int crossings = 0;
      for (int k = 0; k < 3; ++k) crossings += sg[k] * sg[(k + 1) % 3] < 0;
      if (crossings == 0) {
        emit(t[0], t[1], t[2], p);
        continue;
      }
      split_face[p] = 1;
      if (crossings == 1) {
        // One corner on the plane, the other two on opposite sides: two triangles.
        int k = 0;
        while (sg[k] != 0) ++k;
        const int v0 = t[k], v1 = t[(k + 1) % 3], v2 = t[(k + 2) % 3];
        const int x = crossing(v1, v2);
        emit(v0, v1, x, p);
        emit(v0, x, v2, p);
        continue;
      }
      // A lone corner v0 on one side: a triangle at v0 and a quad split by its shorter diagonal.
      int k = 0;
      while (sg[k] == sg[(k + 1) % 3] || sg[k] == sg[(k + 2) % 3]) ++k;
      const int v0 = t[k], v1 = t[(k + 1) % 3], v2 = t[(k + 2) % 3];
      const int x01 = crossing(v0, v1), x20 = crossing(v2, v0);
      emit(v0, x01, x20, p);
      if ((pts[x01] - pts[v2]).squaredNorm() <= (pts[v1] - pts[x20]).squaredNorm()) {
        emit(x01, v1, v2, p);
        emit(x01, v2, x20, p);
      } else {
        emit(x01, v1, x20, p);
        emit(v1, v2, x20, p);
      }
    }
    tris = std::move(next);
    fparent = std::move(next_parent);
  }
  out.split_faces = static_cast<int>(std::count(split_face.begin(), split_face.end(), 1));
  out.face_parent = std::move(fparent);
  out.vertex_parent = std::move(vparent);
  out.mesh = Mesh(TriangleSoup{std::move(pts), std::move(tris)});
  return out;
}

}  // namespace windplan
