#pragma once
// Bounded exact window propagation: the globally shortest polyhedral geodesic between two mesh
// vertices, or the proof that none is shorter than a given upper bound.
//
// Chen and Han's window propagation with Xin and Wang's vertex filter ("Improving Chen and Han's
// algorithm on the discrete geodesic problem", ACM TOG 2009), searched best-first as A*: every
// window (an interval of an edge lit by one unfolded pseudo-source) has the lower bound
//   sigma + min |I x| + min |x t|   over the points x of its interval,
// (pseudo-source distance, straight unfolded distance to the interval, Euclidean distance in
// space from the interval to the target, which no surface path can beat). Windows and vertex
// events whose bound reaches the best length known (the target's distance found so far, or
// `upper_bound`, e.g. the length of a locally shortest geodesic already found) are dropped, and
// the search stops when the smallest bound in the queue reaches it: what remains is a corridor
// around the geodesic instead of the whole mesh.
//
// A window is dropped when an endpoint vertex of its edge reaches its far end more cheaply along
// the edge (d(A) + x is increasing faster than the window's distance, so the whole window is
// beaten): the exact part of ICH's filter. The windows on one edge, lit from either side, also
// cut each other from their ends where one is shorter by more than round-off (Mitchell, Mount and
// Papadimitriou's window intersection, geometry/geodesic/window_distance.h): this cut the windows
// of a search by 3x on the bunnies (bench/README.md, session 6). Saddle and boundary vertices are
// pseudo-sources.
//
// Order: without an upper bound, A* (the target is reached first, then the bound prunes); with
// one, Dijkstra's order by the distance from the source, pruned by the same bound (a window is
// then propagated after the shorter windows that may cut it). A search to one target with the
// target bound gets one before it starts: the bound's graph path straightened into a locally
// shortest geodesic, usually D itself (geometry/geodesic/target_bound.h, step 1; 8-14 % fewer
// windows than A* on the benchmark meshes, bench/README.md, session 23).
// The queue holds halfedges, each at the smallest key of the windows queued on it, and a
// halfedge out of the queue propagates all of them at once (Qin et al.'s list at a time, "Fast
// and exact discrete geodesic computation based on triangle-oriented wavefront propagation",
// SIGGRAPH 2016): its data is read once while in cache (bench/README.md, session 12: 2-7 % more
// windows, 9-13 % less time per path at the median, 16-25 % at the mean).
// The queue is a radix heap (geometry/geodesic/radix_queue.h): both orders are monotone.
// Euclidean metric only (the geodesic core uses it for Euclidean queries between vertices; see
// geodesic_between in geometry/geodesic/geodesic.h). No CGAL: geometry/geodesic/exact_geodesic.h is
// the reference the tests compare with.
#include <limits>
#include <string>
#include <vector>

#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/target_bound.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_order.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

struct WindowSearchOptions {
  /// Only paths strictly shorter than this are looked for (mesh units; +infinity: any).
  double upper_bound = std::numeric_limits<double>::infinity();
  /// Give up (complete = false) after this many windows were created (0: no limit; searches to
  /// a target only, counted per target by shortest_paths_by_windows, whose next target goes on
  /// from there; checked after each halfedge's list, so a search may end a list past it).
  /// A search to a target holds a 16-byte record of every window it propagates (its path is
  /// built back through them) and 64 bytes per window of its wavefront (bench/README.md,
  /// session 14: median 10K windows at 20K faces, 283K and a p90 of 1.37M at 300K faces; the
  /// wavefront 1-3 % of them).
  long max_windows = 0;
  /// A full run (geodesic_distances_by_windows) gives the slot of a window it has propagated
  /// (or that died) to a later one, so that only the wavefront stays in memory (at 300K faces
  /// 106 MB against 1.17 GB, bench/README.md, session 11). No effect on a search to a target,
  /// which always does (keeping a 16-byte record of each window propagated for its path).
  bool reuse_windows = true;
  /// shortest_paths_by_windows: a search that holds more than this many windows' worth of memory
  /// after a target starts afresh for the next (0: every target afresh). Counted as the window
  /// slots held (64 bytes each) and a quarter of the path records of the windows propagated (16
  /// bytes each): 4M is 256 MB per thread, plus the queue. (Since session 14, when a search
  /// began to recycle its slots, a search restarts after about four times as many windows
  /// propagated as before: bench/README.md.) Checked between targets, so a far target's search
  /// may go past it.
  long resume_limit = 1L << 22;
  /// A search to a target (shortest_path_by_windows; each target of shortest_paths_by_windows)
  /// keys its windows with the lower bound of geometry/geodesic/target_bound.h as well as the
  /// straight distance, when the pair bends (target_bound.min_detour). Only the work changes:
  /// every distance stays exact (bench/README.md, session 15: 20-50 % less time per path at the
  /// mean, p90 windows halved).
  bool use_target_bound = true;
  TargetBoundOptions target_bound;

  bool is_valid(std::string* why) const;
};

struct WindowSearchResult {
  /// A path shorter than upper_bound was found: distance and path are set.
  bool found = false;
  /// The search ran to its end (false: max_windows stopped it; then found is false).
  bool complete = true;
  double distance = std::numeric_limits<double>::infinity();
  /// The corridor of the shortest path: the strip of its legs between the pseudo-source
  /// vertices it passes, joined at them, with crossings inside the windows (a start for
  /// refine_path, whose funnel straightens it to the exact geodesic of the corridor).
  SurfacePath path;
  std::vector<int> vertices_passed;  ///< pseudo-source vertices on the path, source side first
  long windows = 0;                  ///< windows created
  long window_slots = 0;             ///< the most windows held in memory at once
  long windows_propagated = 0;       ///< windows propagated
  long vertex_events = 0;            ///< pseudo-source vertices expanded
  double time_ms = 0.0;
};

/// What the window search reads of an interior halfedge h of the renumbered copy when it
/// propagates a window across face(h), in one cache line (the mesh's own arrays would take a
/// line each): h's frame (from(h) at the origin, to(h) on the positive x axis, the corner of
/// face(h) opposite h at (cx, cy), cy >= 0), the lengths of the face's other two edges, and the
/// vertices and halfedges around.
struct alignas(64) HalfedgeFrame {
  double len, cx, cy;
  double len_prev, len_next;  // the lengths of prev(h) (corner -> from(h)) and next(h)
  int from, to, opposite;     // from(h), to(h), the corner
  int twin;                   // twin(h)
  int out_prev, out_next;     // twin(prev(h)), twin(next(h)); -1: a boundary edge
};

/// A face seen from one of its corners v: the other corners (next, then the one after), the
/// lengths of v -> next, v -> after and next -> after, and the face's frame (v at the origin,
/// next at (len, 0), after at (cx, cy), cy >= 0).
struct RingCorner {
  int next, after;
  double len, len_after;
  double cx, cy;
  double len_across;
};

/// Per-mesh data of the window search, built once per mesh (O(V log V + F log F)). The search
/// runs on a copy of the mesh renumbered for memory locality (geometry/mesh/mesh_order.h) and
/// answers in the mesh's own numbering; the arrays below are in the copy's. (The copy costs
/// as much memory as the mesh, and its maps 8 bytes per face: about 20 MB at 300K faces.)
struct WindowMesh {
  MeshOrder order;
  /// Per vertex: 1 for the vertices geodesics may pass through (saddle: cone angle >=
  /// 2 pi - 1e-9, flat and boundary vertices), 0 for the others.
  std::vector<char> pseudo_source;
  /// Per interior halfedge.
  std::vector<HalfedgeFrame> frame;
  /// Per interior halfedge h: the angle at from(h) in face(h) (Mesh::corner_angle, radians).
  /// A saddle's expansion sums its corners' angles; an atan2 per corner each time took 3 % of
  /// the time per path at 20K faces (bench/README.md, session 23; 8 bytes per halfedge).
  std::vector<double> corner_angle;
  /// The faces around each vertex v, as seen from v: ring[ring_start[v] .. ring_start[v + 1]),
  /// in ccw_rotate order (geometry/geodesic/target_bound.h reads a vertex's faces in one
  /// sweep instead of a chain of dependent loads; 40 bytes per corner).
  std::vector<int> ring_start;
  std::vector<RingCorner> ring;
  /// The longest edge (mesh units; geometry/geodesic/target_bound.h).
  double max_edge = 0.0;
  /// The vertex graph with the diagonals across convex pairs of faces (geometry/geodesic/
  /// edge_path.h, with the edges they cross), whose shortest paths are about a per cent longer
  /// than the geodesics (1.2 % at the median of the 50 benchmark pairs at 20K faces,
  /// bench/README.md, session 23), not a few per cent: target_bound.h's path for U (16 bytes
  /// per entry, about 12 entries per vertex).
  EdgeGraph graph;
};
WindowMesh prepare_window_mesh(const Mesh& mesh);

/// Landmark distance fields for tighter A* bounds: geometry/geodesic/window_landmarks.h.
struct Landmarks;

/// Exact geodesic distances from vertex `source` to every vertex (+infinity on other
/// components): the full window propagation.
/// \throw InputError when the vertex is out of range.
/// `stats` (optional) receives the run's counts (no distance, path or time). `options` may only
/// switch reuse_windows (a full run has no upper_bound and no max_windows: ConfigError).
std::vector<double> geodesic_distances_by_windows(const Mesh& mesh, const WindowMesh& window_mesh,
                                                  int source,
                                                  const WindowSearchOptions& options = {},
                                                  WindowSearchResult* stats = nullptr);

/// The shortest path from vertex `source` to vertex `target` if it is shorter than
/// options.upper_bound. `window_mesh` is prepare_window_mesh(mesh); `landmarks` (optional)
/// tighten the A* bounds. Thread-safe (per-thread buffers).
/// \throw InputError when a vertex index is out of range.
WindowSearchResult shortest_path_by_windows(const Mesh& mesh, const WindowMesh& window_mesh,
                                            int source, int target,
                                            const WindowSearchOptions& options = {},
                                            const Landmarks* landmarks = nullptr);

/// The shortest paths from vertex `source` to each vertex of `targets` (results[i] for
/// targets[i]; a target equal to the source gets found = false), by one search resumed from
/// target to target, the nearest in space first: the windows and distances found for one
/// target are the start of the next (up to options.resume_limit windows).
/// Each result's windows, vertex_events and time are its own target's share. Exact as
/// shortest_path_by_windows, for less work when the targets share a source
/// (bench/README.md, session 13).
/// \throw InputError when a vertex index is out of range.
std::vector<WindowSearchResult> shortest_paths_by_windows(const Mesh& mesh,
                                                          const WindowMesh& window_mesh, int source,
                                                          const std::vector<int>& targets,
                                                          const WindowSearchOptions& options = {},
                                                          const Landmarks* landmarks = nullptr);

}  // namespace windplan
