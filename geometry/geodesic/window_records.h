#pragma once
// The exact window search's data (internal to geometry/geodesic, see window_search.h): windows,
// queue events, a query's records of vertices and halfedges, the per-thread buffers that hold
// them, and the checks shared by the search's entry points.
//
// Window frame: a window lives on halfedge h and propagates into face(h). In h's frame from(h)
// is the origin, to(h) is (L, 0), the third corner of face(h) has y > 0 and the unfolded
// pseudo-source I = (sx, sy) has sy <= 0 (it lies on the side of face(twin(h))). A point (x, 0)
// of the window's interval [b0, b1] is at distance sigma + |I - (x, 0)| from the source.
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <vector>

#include "geometry/geodesic/geodesic_windows.h"
#include "geometry/geodesic/radix_queue.h"

namespace windplan {
namespace window_search {

using Clock = std::chrono::steady_clock;

struct Vec2 {
  double x, y;
};
inline Vec2 operator-(const Vec2& a, const Vec2& b) { return {a.x - b.x, a.y - b.y}; }
inline double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }
inline double dot(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }
inline double norm(const Vec2& a) { return std::sqrt(a.x * a.x + a.y * a.y); }

// One cache line: the walk along an edge's windows (Search::compete) reads the b0, b1 and next
// of one listed window after another, at random places in memory (8.4 windows per new window
// at 100K faces, most not overlapping it: bench/README.md, sessions 9 and 12).
struct alignas(64) Window {
  int h;          // its edge's length is WindowMesh::frame[h].len (Search::length)
  int parent;     // the record of the window propagated into this one (PathRecord; a full run
                  // with reused slots: its slot, never read); < 0: lit by vertex -(parent + 1)
  int next = -1;  // the next window on the same edge (Scratch::head), -1: last
  double b0, b1;
  Vec2 source;         // I in h's frame
  double sigma;        // distance of the pseudo-source from the source
  double bound = 0.0;  // lower bound of the paths to the target through the window (A* key)
};
static_assert(sizeof(Window) == 64, "a window fills one cache line");

// What a search to a target keeps of a window it propagated, once its slot has gone to a later
// window: the path is built back through these. Written in order, a quarter of a window's
// bytes and never read while searching, so that the windows alive (the wavefront, 1-3 % of
// those made) stay few and in cache.
struct PathRecord {
  int h;       // the window's halfedge
  int parent;  // the record of the window propagated into it; < 0: lit by vertex -(parent + 1)
  double mid;  // the middle of its interval on h, as it was queued (the path crosses h there)
};
static_assert(sizeof(PathRecord) == 16, "a quarter of a window");

// The ray that gave a saddle vertex its distance, for that vertex's expansion (which lights
// only the faces a shortest path can continue into): the window's halfedge and pseudo-source
// in its frame. Valid for a vertex whose VertexRecord names a provider window.
struct Arrival {
  int h;
  Vec2 source;
};

// A window lit by `parent` (>= 0), or by vertex -(parent + 1) directly.
inline Window make_window(int h, double b0, double b1, Vec2 source, double sigma, int parent) {
  Window w;
  w.h = h;
  w.parent = parent;
  w.b0 = b0;
  w.b1 = b1;
  w.source = source;
  w.sigma = sigma;
  return w;
}

struct Event {
  double key;
  int index;         // >= 0: halfedge (its list of queued windows); < 0: vertex -(index + 1)
  unsigned tag = 0;  // a halfedge's: current while equal to its record's tag
};

// Where the ray from I through X meets the line P + s (Q - P): s (NaN when parallel).
inline double ray_hit(const Vec2& I, const Vec2& X, const Vec2& P, const Vec2& Q) {
  const Vec2 d = X - I;
  const double den = cross(Q - P, d);
  if (den == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return cross(I - P, d) / den;
}

// A query's record of a vertex: its distance and what gave it.
struct VertexRecord {
  unsigned stamp;
  int provider_window;  // the window whose ray reached it (its PathRecord; a full run with reused
                        // slots: its slot); -1: an edge from provider_vertex
  int provider_vertex;
  double dist;
  // An event in the queue will expand it at this distance. (Its key cannot tell: the queue
  // may raise a key, geometry/geodesic/radix_queue.h.)
  bool pending;
};

// A query's record of a halfedge (one cache line's worth, read together).
struct HalfedgeRecord {
  unsigned stamp;
  int head;  // the first of its windows (linked through Window::next), -1: none
  // One angle, one split (Xin and Wang): the shortest distance to the corner opposite h that
  // a window on h gave (+infinity: none yet), and where that ray crossed h.
  double split_dist, split_x;
  double target_x, target_y;  // the target in h's frame (target_in_frame); NaN: not yet
  // The key of the halfedge's current queue entry (+infinity: none) and that entry's tag
  // (entries with an older tag are stale).
  double queued_key;
  unsigned tag;
};

// Per-thread buffers reused across queries (56 bytes per vertex with its arrival, 56 per
// halfedge, plus 64 per window slot, 16 per path record and 16 per queue entry of the largest
// search so far): the records are valid when their stamp is the query's (no O(V) clearing per
// query), an arrival when its vertex's record is and names a provider window.
struct Scratch {
  unsigned stamp = 0;
  std::vector<VertexRecord> vertices;
  std::vector<HalfedgeRecord> halfedges;
  std::vector<Window> windows;
  std::vector<PathRecord> records;
  std::vector<Arrival> arrivals;  // per vertex
  RadixQueue<Event> queue;
  std::vector<int> outgoing;
  TargetBound target_bound;  // a search to one target's (geometry/geodesic/target_bound.h)

  void begin(const Mesh& mesh) {
    const std::size_t nv = mesh.num_vertices(), nh = mesh.num_halfedges();
    if (vertices.size() != nv || halfedges.size() != nh || ++stamp == 0) {
      stamp = 1;
      vertices.assign(nv, VertexRecord{0, -1, -1, 0.0, false});
      arrivals.assign(nv, Arrival{-1, {0.0, 0.0}});
      halfedges.assign(nh, HalfedgeRecord{0, -1, 0.0, 0.0, 0.0, 0.0, 0.0, 0});
    }
    windows.clear();
    records.clear();
    queue.clear();
  }
};

/// One set of buffers per thread, shared by every kind of search (a thread that builds
/// landmark fields and then searches paths keeps one, not two). Defined in geodesic_windows.cpp.
Scratch& thread_scratch();

/// \throw InputError when a vertex is out of range, ConfigError when window_mesh is not
/// prepare_window_mesh(mesh)'s.
void check_inputs(const Mesh& mesh, const WindowMesh& window_mesh,
                  std::initializer_list<int> vertices);

/// check_inputs, and ConfigError for invalid options or landmark fields of another mesh.
void check_query(const Mesh& mesh, const WindowMesh& window_mesh,
                 std::initializer_list<int> vertices, const WindowSearchOptions& options,
                 const Landmarks* landmarks);

/// A search's path and passed vertices, found on the renumbered copy, in the mesh's numbering.
void path_in_original(const Mesh& mesh, const MeshOrder& order, WindowSearchResult* result);

}  // namespace window_search
}  // namespace windplan
