// Exact window searches from one source to several targets, one after the other
// (shortest_paths_by_windows in geometry/geodesic/geodesic_windows.h).
#include <memory>

#include "geometry/geodesic/geodesic_windows.h"
#include "geometry/geodesic/window_search.h"

namespace windplan {

using window_search::check_inputs;
using window_search::check_query;
using window_search::Clock;
using window_search::path_in_original;
using window_search::Search;

std::vector<WindowSearchResult> shortest_paths_by_windows(const Mesh& mesh,
                                                          const WindowMesh& window_mesh, int source,
                                                          const std::vector<int>& targets,
                                                          const WindowSearchOptions& options,
                                                          const Landmarks* landmarks) {
  check_query(mesh, window_mesh, {source}, options, landmarks);
  for (const int t : targets) check_inputs(mesh, window_mesh, {t});
  const MeshOrder& order = window_mesh.order;
  // Nearest first (in space): a near target's search is mostly on the way to the far ones.
  std::vector<int> turn(targets.size());
  for (std::size_t i = 0; i < turn.size(); ++i) turn[i] = static_cast<int>(i);
  const Vec3& ps = mesh.position(source);
  std::stable_sort(turn.begin(), turn.end(), [&](int i, int j) {
    return (mesh.position(targets[i]) - ps).squaredNorm() <
           (mesh.position(targets[j]) - ps).squaredNorm();
  });
  std::vector<WindowSearchResult> results(targets.size());
  const int s = order.vertex_to_local[source];
  std::unique_ptr<Search<false, true>> search;
  for (const int i : turn) {
    const auto t0 = Clock::now();
    const int t = targets[i];
    WindowSearchResult& result = results[i];
    if (t != source) {
      const int local = order.vertex_to_local[t];
      // A search holding many windows starts afresh (WindowSearchOptions::resume_limit).
      if (search != nullptr &&
          search->windows_held() > static_cast<std::size_t>(options.resume_limit))
        search.reset();
      if (search == nullptr) {
        search = std::make_unique<Search<false, true>>(window_mesh, s, local, options, landmarks);
        result = search->run();
      } else {
        result = search->run_to(local);
      }
      path_in_original(mesh, order, &result);
    }
    result.time_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  }
  return results;
}

}  // namespace windplan
