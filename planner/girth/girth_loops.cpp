#include "planner/girth/girth_loops.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace windplan {

std::vector<std::vector<int>> alternative_edge_loops(const Mesh& mesh, const EdgeGraph& g,
                                                     const std::vector<signed char>& shift, int p,
                                                     const std::vector<int>& first, int max_loops,
                                                     double window) {
  std::vector<std::vector<int>> loops;
  const int nv = mesh.num_vertices();
  if (max_loops <= 0 || p < 0 || p >= nv) return loops;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Full Dijkstra on the double cover from (p, 0): node 2 v + c.
  std::vector<double> dist(2 * static_cast<std::size_t>(nv), kInf);
  std::vector<int> parent(2 * static_cast<std::size_t>(nv), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[2 * p] = 0.0;
  queue.emplace(0.0, 2 * p);
  while (!queue.empty()) {
    const auto [d, node] = queue.top();
    queue.pop();
    if (d > dist[node]) continue;
    const int v = node >> 1, c = node & 1;
    for (int i = g.offsets[v]; i < g.offsets[v + 1]; ++i) {
      const int next = 2 * g.neighbors[i] + (c ^ (shift[i] != 0 ? 1 : 0));
      const double nd = d + g.weights[i];
      if (nd < dist[next]) {
        dist[next] = nd;
        parent[next] = node;
        queue.emplace(nd, next);
      }
    }
  }
  auto D = [&](int q) { return dist[2 * q] + dist[2 * q + 1]; };
  if (!(D(p) < kInf)) return loops;
  double best = kInf;
  for (int q = 0; q < nv; ++q) best = std::min(best, D(q));
  // Vertices on or next to a loop already taken.
  std::vector<char> taken(nv, 0);
  auto take = [&](const std::vector<int>& cycle) {
    for (int v : cycle) {
      taken[v] = 1;
      for (int i = g.offsets[v]; i < g.offsets[v + 1]; ++i) taken[g.neighbors[i]] = 1;
    }
  };
  take(first);
  std::vector<std::pair<double, int>> minima;
  for (int q = 0; q < nv; ++q) {
    const double dq = D(q);
    if (taken[q] || !(dq <= window * best)) continue;
    bool local_min = true;
    for (int i = g.offsets[q]; i < g.offsets[q + 1] && local_min; ++i)
      local_min = dq <= D(g.neighbors[i]);
    if (local_min) minima.emplace_back(dq, q);
  }
  std::sort(minima.begin(), minima.end());
  for (const auto& [dq, q] : minima) {
    if (static_cast<int>(loops.size()) >= max_loops) break;
    if (taken[q]) continue;
    // (p,0) -> (q,0), then (q,0) -> (p,1): the path (p,0) -> (q,1) reversed with copies flipped.
    std::vector<int> there, back;
    for (int n = 2 * q; n >= 0; n = parent[n]) there.push_back(n >> 1);
    for (int n = 2 * q + 1; n >= 0; n = parent[n]) back.push_back(n >> 1);
    std::reverse(there.begin(), there.end());  // p ... q
    // back is q ... p already (walked from (q,1) to (p,0)).
    std::vector<int> cycle = there;
    cycle.insert(cycle.end(), back.begin() + 1, back.end() - 1);  // without q again and p
    std::vector<int> clean = remove_spurs(cycle);
    // A spur at p (p, x, ..., x) means p is not on the loop proper.
    if (clean.size() < 3 || clean.front() != p || clean.back() == clean[1]) continue;
    take(clean);
    loops.push_back(std::move(clean));
  }
  return loops;
}

}  // namespace windplan
