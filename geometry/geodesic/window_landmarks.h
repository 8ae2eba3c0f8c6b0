#pragma once
// Landmarks for the exact window search (geometry/geodesic/geodesic_windows.h): exact distance
// fields from a few vertices, whose triangle inequality bounds the distance left to the target
// far better than the straight distance in space where a path winds around the surface (ALT:
// Goldberg and Harrelson, "Computing the shortest path: A* search meets graph theory", SODA
// 2005). Built once per mesh, a full window propagation per landmark (bench/README.md, sessions 6
// and 11: 30-47 % fewer windows per path with 8, at 4-5 s of CPU per field at 300K faces).
#include <vector>

#include "geometry/geodesic/geodesic_windows.h"

namespace windplan {

/// Exact geodesic distance fields from a few landmark vertices, for A* lower bounds by the
/// triangle inequality: d(x, t) >= |d(L, t) - d(L, x)| (Goldberg and Harrelson's ALT), which
/// bound paths that wind around the surface far better than the straight distance in space.
struct Landmarks {
  int count = 0;
  std::vector<int> vertices;
  std::vector<double> dist;  ///< dist[v * count + k]: from landmark k to vertex v
};

/// ALT lower bound on d(x, t) over the points x of the edge from vertex a to vertex b (its
/// length `length`) at arc lengths s in [s0, s1] from a: max over the landmarks L of
/// |d(L, t) - d(L, x)|, with d(L, x) bracketed by d(L, a) +- s and d(L, b) +- (length - s)
/// (a distance field is 1-Lipschitz along the edge) at the s of the interval that weakens the
/// bracket most. `target_dist` holds d(L, t) per landmark. 0 where a field is infinite.
double landmark_edge_bound(const Landmarks& landmarks, const double* target_dist, int a, int b,
                           double length, double s0, double s1);

/// `count` landmarks chosen farthest-point in space, their exact distance fields built in
/// parallel (parallel_for_index): each is a full window propagation.
Landmarks compute_landmarks(const Mesh& mesh, const WindowMesh& window_mesh, int count);

}  // namespace windplan
