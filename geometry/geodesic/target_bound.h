#pragma once
// A lower bound of the distance to a target for the exact window search's A* keys
// (geometry/geodesic/window_search.h), much tighter than the straight distance where the
// geodesic bends round the surface.
//
// The straight distance |x t| bounds a path from x to t from below, but poorly where the surface
// bulges between them: a pair whose geodesic is 1.57x its straight distance makes the A* search
// explore most of a 100K-face bunny (bench/README.md, session 14). This bound is built per query:
//   1. U: a path from the target to the source along edges and diagonals across convex pairs of
//      faces (A* on that graph), or the caller's upper bound if smaller: U >= D, the distance
//      sought, unless the caller's bound is below D, when the search finds no path anyway.
//      Every point y of a shortest path then has |y s| + |y t| <= D <= U: the path lies in the
//      ellipsoid with foci s and t.
//      That path is about 1 % longer than D; straightened in its corridor into a locally
//      shortest geodesic (geometry/geodesic/refine_path.h) it is usually D itself (39 of the 50
//      benchmark pairs at 20K faces to 1e-9, 45 within 6e-5): its length l, a surface path's,
//      becomes U (times 1 + 1e-9 against round-off) and TargetBound::local_length. The window
//      search then knows a length within a hair of D from its start and runs in Dijkstra's
//      order below it, which leaves fewer windows cut in vain than A* order does (8-14 % fewer
//      windows on the four benchmark meshes, bench/README.md, session 23).
//   2. psi: fast marching from the target (point-source updates, each face placing the source
//      from its two known corners, exact where the surface unfolds flat) over the
//      vertices near that ellipsoid: an approximate distance, no bound by itself.
//      Its values are rough: a face's corners reached from different faces make a quarter of
//      the faces of the 20K bunny steeper than 1.01, and 3 divides the whole bound by its L.
//      So each vertex, as the marching accepts it, is lowered to the largest value that keeps
//      every face it completes (its other two corners accepted) at most 1.02 steep, when one
//      value does for all of them (TargetBoundOptions::clamp_slope; the target's own faces,
//      steep as a cone's apex, are left to 4). L then falls to about 1.02, and h(s) on the
//      hardest pairs at 20K from 0.93-0.95 of D to 0.96-0.98: 5-28 % fewer windows on the
//      four benchmark meshes (bench/README.md, session 24). Any values make a bound (3).
//   3. What makes it a bound: psi is linear on each face, with slope g_f there. Along a shortest
//      path from x to t, which crosses each face at most once in a segment of length l_f, psi
//      changes by at most min(g_f l_f, spread_f) per face (spread_f: psi's range over the
//      face's corners), so psi(x) - psi(t) <= L d(x, t) + E for any L >= 1, with
//      E = sum over the faces met by the ellipsoid with g_f > L of spread_f (1 - L / g_f).
//      (In a face: if g_f l_f <= spread_f, g_f l_f - L l_f = (g_f - L) l_f <= (g_f - L)
//      spread_f / g_f; otherwise spread_f - L l_f < spread_f - L spread_f / g_f.)
//   Hence h(x) = (psi(x) - psi(t) - E) / L <= d(x, t) at every point of the shortest path.
//   4. The steepest faces lie round the target, at the apex of the distance's cone, which no
//      linear piece follows: the path's last stretch, inside {psi <= r}, is left out. The
//      path from x first reaches psi = r at a point y of a face that the level set crosses,
//      with d(y, t) >= rho(r), the least distance from t to those level-set segments; so
//      h(x) = (psi(x) - r - E(r)) / L + rho(r) <= d(x, t) wherever psi(x) > r, E(r) summed
//      over the faces with a corner above r. r (0, or 1-16 hundredths of U) and L are
//      chosen to make h largest halfway, where psi = psi(s) / 2.
//   5. A face each of whose points y has |y s| + h(y) > U meets no shortest path from s to t
//      (on one, |y s| + h(y) <= d(s, y) + d(y, t) = D <= U by 3 and 4); the bound at a point
//      of such a path needs only the faces of the path's tail, so L and E are chosen again
//      without those faces.
//   6. E by level: near the target only the steep faces below it count. A face the tail from
//      x crosses holds a point y with d(y, t) <= d(x, t), so its least corner value is at
//      most psi(y) <= q + E, q = r + L (d(x, t) - rho) (3 and 4 at y). With E(p) the excess of
//      the faces whose least corner is at most p (nondecreasing), psi(x) <= q + E(q + E); had
//      q < psi(x) - E(psi(x) + E), then q + E(q + E) < psi(x). So
//      h(x) = (psi(x) - r - E(psi(x) + E)) / L + rho(r) <= d(x, t). Along an edge psi stays
//      within the largest spread of a face of either end's value, so each vertex takes E at
//      its value + that spread + E and h stays linear along edges; E(p) is tabulated in 256
//      levels, each face counted one level early. 4-6 % fewer windows on the four benchmark
//      meshes (bench/README.md, session 20).
//   On the 20K bunny h(s) is 0.94-0.98 of the distance (median 0.97 over the benchmark's pairs
//   with a bound; 0.93-0.98 and 0.95 without 2's clamp), against 0.64 for the straight distance
//   on the longest pair at 100K faces (bench/README.md, sessions 15, 16 and 24).
// The window search keys a window with max(straight bound, this bound), exact as before: the
// bound holds on the shortest path, which is all the A* stop needs (a window off it keyed too
// high is dropped, and no shortest path passes through it). h is not 1-Lipschitz where a
// face's slope exceeds L, so a child's key may fall below its parent's; the radix queue then
// raises it to the key last popped, which for the windows of the shortest path is at most D
// (by induction from the source: each is pushed while its parent, keyed <= D, is propagated),
// so they all come out before the search stops.
// tests/geometry/geodesic/target_bound_test.cpp checks h <= d(v, t) against CGAL at every
// vertex v with d(s, v) + d(v, t) <= U, on meshes where fast marching's slopes exceed 1. The
// proof covers them too: every point z of a shortest path from v to t has d(s, z) + d(z, t)
// <= U, so steps 3 and 4 hold at z (the first bound), z lies on no face step 5 rules out, and
// the tail from z crosses only faces L and E count, and those below its level for 6.
#include <limits>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/geodesic/bucket_queue.h"

namespace windplan {

struct WindowMesh;  // geometry/geodesic/geodesic_windows.h

struct TargetBoundOptions {
  /// Built only when U (the length of a path along edges and diagonals, about 1 % above the
  /// geodesic's, or that path straightened) is at least this many times the straight distance
  /// |s t| (dimensionless): below, the straight distance is already within this factor of the
  /// geodesic's and the field would cost more than it saves (bench/README.md, sessions 15-16:
  /// 1.1 when U ran along edges only, a few per cent longer).
  double min_detour = 1.08;
  /// ... or when U is at least this many of the mesh's longest edge (dimensionless): on a long
  /// pair the straight distance's band holds so many windows that even a nearly straight pair
  /// gains (bench/README.md, session 16). +infinity: by min_detour alone.
  double min_edges = 60.0;
  /// Straighten the path of step 1 into a locally shortest geodesic of its corridor and take
  /// its length as U (step 1). False: U is the graph path's length, and the search runs as A*.
  bool straighten_upper = true;
  /// Step 2's clamp (dimensionless, >= 1; 0: none): as the marching accepts a vertex, its value
  /// is lowered to the largest that keeps every face it completes at most this steep, where
  /// that is possible for all of them (faces round the target excepted). 1.02 made the fewest
  /// windows on the benchmark meshes (1.015 and 1.03 more: bench/README.md, session 24).
  double clamp_slope = 1.02;

  bool is_valid(std::string* why) const;
};

/// The bound of one query, in the numbering of the window mesh's renumbered copy. Reused from
/// query to query (its arrays keep their size; a stamp marks what belongs to the current one).
struct TargetBound {
  bool active = false;  ///< false: no bound (straight distance only)
  double upper = std::numeric_limits<double>::infinity();  ///< U (mesh units)
  double slope = 1.0;   ///< L (dimensionless, >= 1)
  double excess = 0.0;  ///< E (mesh units)
  double radius = 0.0;  ///< r: {psi <= r} round the target left out (mesh units; 0: none)
  long vertices = 0;    ///< vertices given a value by the fast marching
  long faces = 0;       ///< faces whose slopes entered L and E
  long faces_out = 0;   ///< steep faces step 5 found on no shortest path (left out of L and E)
  long clamped = 0;     ///< vertices whose value step 2's clamp lowered
  /// The length of the straightened path of step 1 (mesh units; +infinity: none, e.g. the
  /// option is off or the straightening failed). A surface path's length, so >= D.
  double local_length = std::numeric_limits<double>::infinity();

  /// Step 6's table: entry i (0..255) is the excess of the steep faces whose least corner
  /// value is below (i + 1) w, w = level_width(), each face counted one level early; a vertex
  /// of value p takes the entry of p + (the largest face spread) + E. Empty: E at every level
  /// (e.g. no face steeper than L). Nondecreasing, at most `excess`.
  const std::vector<double>& excess_by_level() const { return by_level_; }
  double level_width() const { return level_width_; }  ///< w (mesh units)
  /// The lower bound at vertex v (mesh units; -infinity: none, e.g. v far from the ellipsoid).
  /// Linear along every edge between its ends' values.
  double at(int v) const {
    const State& s = state_[v];
    return active && s.mark == stamp_ && s.accepted ? s.value
                                                    : -std::numeric_limits<double>::infinity();
  }

 private:
  friend void build_target_bound(const WindowMesh&, int, int, double, const TargetBoundOptions&,
                                 TargetBound*);
  struct Item {
    double key;
    int v;
  };
  // Per vertex, in one line with its neighbours' (the passes read them together).
  struct State {
    unsigned mark;  // == stamp_: the fields below are this query's
    char accepted;  // given its final value by pass 2
    char closed;    // settled by pass 1
    double value;   // pass 2's psi, then h
    double graph;   // pass 1's path length from the target (edges and diagonals)
    double foci;    // |v s| + |v t|; < 0: not yet
    double to_target;  // |v t| (with foci)
  };
  // A face whose slope exceeds the least limit tried: its slope, spread and largest psi.
  struct Steep {
    double slope, spread, top;
    double low;     // least psi of its corners
    double near_s;  // least |v s| of its corners, less its longest edge
    char out;       // on no shortest path from the source (ruled out by a first bound)
  };
  unsigned stamp_ = 0;
  std::vector<State> state_;
  std::vector<Steep> steep_;
  std::vector<int> order_;  // vertices accepted by pass 2
  std::vector<int> parent_entry_;  // per vertex: the graph entry that gave it its length in pass 1
  std::vector<double> by_level_;  // step 6: E up to each level of psi
  double level_width_ = 0.0;
  BucketQueue<Item> queue_;
};

/// Builds `bound` for a search from `source` to `target`, vertices of window_mesh's renumbered
/// copy (window_mesh.order.mesh). `upper_bound`: a length the search needs to look below
/// (+infinity: none). Leaves bound->active false when the pair is nearly straight and short
/// (options.min_detour, options.min_edges), the source is unreachable, source == target, or
/// the bound at the source would not be positive.
/// Cost: an A* over the vertex graph, the straightening of its path (O(path) per round of
/// geometry/geodesic/refine_path.h) and a fast marching over the vertices near the ellipsoid,
/// O(n) in them with a bucket queue (plus one step per bucket, a 32nd of the longest edge, up
/// to U); the faces' slopes are read as the marching completes each.
void build_target_bound(const WindowMesh& window_mesh, int source, int target, double upper_bound,
                        const TargetBoundOptions& options, TargetBound* bound);

/// The least distance from t to the level set {psi = r} of the linear interpolant of `value`
/// on the triangle `corner` (+infinity when r is outside the values' range; a face level at r
/// is the caller's case). Step 4's rho(r) is the least of these over the faces it crosses.
double level_set_distance(const Vec3 corner[3], const double value[3], double r, const Vec3& t);

}  // namespace windplan
