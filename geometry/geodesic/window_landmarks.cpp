// Landmark fields and their edge bound (see geometry/geodesic/window_landmarks.h).
#include "geometry/geodesic/window_landmarks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/base/parallel.h"

namespace windplan {

double landmark_edge_bound(const Landmarks& landmarks, const double* target_dist, int a, int b,
                           double length, double s0, double s1) {
  const int k = landmarks.count;
  const double* la = landmarks.dist.data() + static_cast<std::size_t>(a) * k;
  const double* lb = landmarks.dist.data() + static_cast<std::size_t>(b) * k;
  double bound = 0.0;
  for (int i = 0; i < k; ++i) {
    // d(L, x(s)) <= min(d(L, a) + s, d(L, b) + length - s): concave in s, largest where the
    // two lines cross (clamped to [s0, s1]); >= max(d(L, a) - s, d(L, b) - length + s): convex,
    // smallest where those cross.
    const double su = std::clamp(0.5 * (lb[i] + length - la[i]), s0, s1);
    const double upper = std::min(la[i] + su, lb[i] + length - su);
    const double sl = std::clamp(0.5 * (la[i] - lb[i] + length), s0, s1);
    const double lower = std::max(la[i] - sl, lb[i] - length + sl);
    bound = std::max({bound, target_dist[i] - upper, lower - target_dist[i]});
  }
  return std::isfinite(bound) ? bound : 0.0;
}

Landmarks compute_landmarks(const Mesh& mesh, const WindowMesh& window_mesh, int count) {
  Landmarks l;
  if (count <= 0 || mesh.num_vertices() == 0) return l;
  // Farthest-point choice in space: the first is the vertex farthest along the bounding box
  // diagonal, each next one the vertex farthest from those chosen. (Geodesically farthest
  // points need each field before the next choice, one after another; these let the fields
  // be computed in parallel, and bound as well: bench/README.md, session 6.)
  const Vec3 diagonal = mesh.bounding_box().diagonal();
  int next = -1;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.vertex_halfedge(v) < 0) continue;
    if (next < 0 || mesh.position(v).dot(diagonal) > mesh.position(next).dot(diagonal)) next = v;
  }
  std::vector<double> nearest(mesh.num_vertices(), std::numeric_limits<double>::infinity());
  while (next >= 0 && static_cast<int>(l.vertices.size()) < count) {
    l.vertices.push_back(next);
    const Vec3 p = mesh.position(next);
    next = -1;
    double far = 0.0;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      if (mesh.vertex_halfedge(v) < 0) continue;
      nearest[v] = std::min(nearest[v], (mesh.position(v) - p).squaredNorm());
      if (nearest[v] > far) {
        far = nearest[v];
        next = v;
      }
    }
  }
  l.count = static_cast<int>(l.vertices.size());
  std::vector<std::vector<double>> fields(l.count);
  parallel_for_index(l.count, [&](int k) {
    fields[k] = geodesic_distances_by_windows(mesh, window_mesh, l.vertices[k]);
  });
  l.dist.resize(static_cast<std::size_t>(mesh.num_vertices()) * l.count);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    for (int k = 0; k < l.count; ++k)
      l.dist[static_cast<std::size_t>(v) * l.count + k] = fields[k][v];
  return l;
}

}  // namespace windplan
