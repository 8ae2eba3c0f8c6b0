#pragma once
// The exact window search's engine, internal to geometry/geodesic: the Search template behind
// geodesic_windows.cpp (full runs, one target) and geodesic_windows_resume.cpp (one target after
// another), on the data of window_records.h. Each instantiation lives in its own source, so
// that the compiler inlines the hot loops of each as if it were alone (the third instantiation
// in one source had cost the others 3-4 % more instructions: bench/README.md, session 13).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/base/errors.h"
#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/geodesic_windows.h"
#include "geometry/geodesic/window_distance.h"
#include "geometry/geodesic/window_landmarks.h"
#include "geometry/geodesic/window_records.h"

namespace windplan {
namespace window_search {

// kReuse: a full run with reused slots, which keeps no PathRecords (it builds no path); its own
// instantiation, so that neither kind of search pays for the other's bookkeeping (4-8 % per
// path when reuse was a run-time flag, bench/README.md, session 11).
// kResume: a search from one source to several targets, one after the other (run, then
// run_to): it drops nothing for a target's bound, so that its state stays a valid start for
// the next target (its own instantiation for the same reason).
template <bool kReuse, bool kResume = false>
class Search {
 public:
  // On the window mesh's renumbered copy: source and target are its vertices (target < 0:
  // every vertex's distance, Dijkstra order, no bound). Landmark fields are in the original
  // numbering.
  Search(const WindowMesh& window_mesh, int source, int target, const WindowSearchOptions& options,
         const Landmarks* landmarks = nullptr)
      : window_mesh_(window_mesh),
        mesh_(window_mesh.order.mesh),
        original_(window_mesh.order.vertex_from_local.data()),
        pseudo_(window_mesh.pseudo_source),
        frame_(window_mesh.frame.data()),
        source_(source),
        target_(target),
        options_(options),
        target_position_(target >= 0 ? mesh_.position(target) : Vec3::Zero()),
        landmarks_(target >= 0 && landmarks != nullptr && landmarks->count > 0 ? landmarks
                                                                               : nullptr),
        scratch_(thread_scratch()),
        windows_(scratch_.windows),
        records_(scratch_.records),
        queue_(scratch_.queue),
        outgoing_(scratch_.outgoing),
        best_(options.upper_bound),
        distance_order_(target < 0 || std::isfinite(options.upper_bound)),
        recycle_(kReuse || target >= 0) {
    scratch_.begin(mesh_);
    copy_target_landmarks();
    build_bound();
  }

  // The distances of a full run (target < 0), in the original numbering.
  std::vector<double> distances() const {
    std::vector<double> d(mesh_.num_vertices());
    for (int v = 0; v < mesh_.num_vertices(); ++v) d[original_[v]] = dist(v);
    return d;
  }

  // A thread keeps its buffers for the next query up to this many windows (about 100 bytes
  // each with the queue: 100 MB per thread, which a batch on 32 threads multiplies); a larger
  // search gives its memory back when it ends (reallocating costs little beside such a
  // search: bench/README.md, session 6, p90 1.35M windows in 554 ms at 300K faces).
  static constexpr std::size_t kKeptWindows = std::size_t{1} << 20;

  ~Search() {
    // (Records are a quarter of a window's bytes.)
    if (windows_.capacity() > kKeptWindows || records_.capacity() > 4 * kKeptWindows) {
      std::vector<Window>().swap(windows_);
      std::vector<PathRecord>().swap(records_);
      queue_.release();
    }
  }

  WindowSearchResult run() {
    relax(source_, 0.0, -1, -1);
    scratch_.vertices[source_].pending = false;  // expanded here, not again by its event
    expand_vertex(source_, 0.0);
    return run_leg();
  }

  // (kResume) The search resumed for another target: every window still listed and every
  // vertex still to expand is keyed for it again, and the search goes on from where it
  // stopped. Exact as a new search is: the windows and distances found so far are real rays
  // and paths, and nothing was dropped for the earlier targets' bounds.
  WindowSearchResult run_to(int target) {
    static_assert(kResume, "a resumable search only");
    retarget(target);
    return run_leg();
  }

  // Windows held: the slots, and the records of those propagated (a quarter of a slot each).
  std::size_t windows_held() const { return windows_.size() + records_.size() / 4; }

 private:
  WindowSearchResult run_leg() {
    WindowSearchResult result;
    while (!queue_.empty() && !aborted_) {
      const Event e = queue_.pop();
      // A halfedge's entry has a key at most every order key, hence every bound, of the
      // windows queued on it, unless the queue raised it to the key last popped (which was at
      // most the bound of the parent, hence of every path through the window): once a key
      // reaches the best length, nothing shorter is left.
      if (e.key >= best_) break;
      if (e.index >= 0) {
        result.windows_propagated += propagate_list(e);
      } else {
        // Expanded once per distance it gets: the first of its events to come out expands it
        // at its current distance, the others are stale.
        const int v = -e.index - 1;
        VertexRecord& r = scratch_.vertices[v];
        if (r.pending && vertex_key(v, r.dist) < best_) {
          r.pending = false;
          expand_vertex(v, r.dist);
        }
      }
    }
    result.windows = created_;
    result.window_slots = static_cast<long>(windows_.size());
    result.vertex_events = vertex_events_;
    result.complete = !aborted_;
    if (target_ < 0 || aborted_ || !(dist(target_) < options_.upper_bound)) return result;
    result.distance = dist(target_);
    result.found = build_path(&result.path, &result.vertices_passed);
    return result;
  }

  // The target bound of geometry/geodesic/target_bound.h for the current target, when the
  // options ask for it and the pair bends enough (a resumed search builds one per target: the
  // windows it keeps are keyed again with it).
  void build_bound() {
    bound_ = nullptr;
    if (target_ < 0 || !options_.use_target_bound) return;
    build_target_bound(window_mesh_, source_, target_, options_.upper_bound,
                       options_.target_bound, &scratch_.target_bound);
    if (scratch_.target_bound.active) bound_ = &scratch_.target_bound;
    // A straightened path's length (target_bound.h, step 1), usually D itself: from here on
    // the search looks for paths no longer than it (best_ keeps a margin of 1e-9: it admits
    // only paths strictly shorter, and U may be D exactly), in Dijkstra's order like any
    // search under an upper bound. (A resumable search keeps its windows for later targets and
    // its A* order.)
    if constexpr (!kResume) {
      if (std::isfinite(scratch_.target_bound.local_length)) {
        best_ = std::min(best_, scratch_.target_bound.upper * (1.0 + 1e-9));
        distance_order_ = true;
      }
    }
  }

  // The target's row of the landmark fields (ALT bounds need d(L, t) for every landmark L; a
  // full run has none).
  void copy_target_landmarks() {
    if (landmarks_ == nullptr) return;
    const int k = landmarks_->count;
    const std::size_t t = original_[target_];
    target_landmark_.assign(landmarks_->dist.begin() + t * k,
                            landmarks_->dist.begin() + (t + 1) * k);
  }

  void retarget(int target) {
    target_ = target;
    target_position_ = mesh_.position(target);
    copy_target_landmarks();
    build_bound();
    // The caller's bound, or a path found already.
    best_ = std::min(options_.upper_bound, dist(target));
    created_ = 0;
    vertex_events_ = 0;
    aborted_ = false;
    queue_.clear();
    for (const int h : touched_) {
      HalfedgeRecord& r = scratch_.halfedges[h];
      r.target_x = r.target_y = std::numeric_limits<double>::quiet_NaN();
      r.queued_key = std::numeric_limits<double>::infinity();
      ++r.tag;
      for (int i = r.head; i >= 0; i = windows_[i].next) {
        double order = 0.0;
        keys(windows_[i], &order, &windows_[i].bound);
        schedule(h, order);
      }
    }
    // (A vertex reached again is listed again.)
    std::sort(pending_vertices_.begin(), pending_vertices_.end());
    pending_vertices_.erase(std::unique(pending_vertices_.begin(), pending_vertices_.end()),
                            pending_vertices_.end());
    std::size_t kept = 0;
    for (const int v : pending_vertices_) {
      const VertexRecord& r = scratch_.vertices[v];
      if (!r.pending) continue;
      pending_vertices_[kept++] = v;
      push({order_key(v, r.dist), -(v + 1)});
    }
    pending_vertices_.resize(kept);
  }

  double dist(int v) const {
    const VertexRecord& r = scratch_.vertices[v];
    return r.stamp == scratch_.stamp ? r.dist : std::numeric_limits<double>::infinity();
  }

  // `window`: the providing window's record (its slot in a full run with reused slots), whose
  // halfedge is ray_h and pseudo-source ray_source; < 0: an edge from from_vertex.
  void relax(int v, double d, int window, int from_vertex, int ray_h = -1,
             Vec2 ray_source = {0.0, 0.0}) {
    if (!(d < dist(v))) return;
    VertexRecord& r = scratch_.vertices[v];
    r = VertexRecord{scratch_.stamp, window, from_vertex, d, false};
    // Its expansion reads the ray's direction (continuation_range).
    if (window >= 0 && pseudo_[v]) scratch_.arrivals[v] = Arrival{ray_h, ray_source};
    if (v == target_) {
      best_ = std::min(best_, d);
      // (A resumable search expands a target that is a pseudo-source for the next targets.)
      if constexpr (!kResume) return;
    }
    if (!pseudo_[v]) return;
    if (kResume || vertex_key(v, d) < best_) {
      push({order_key(v, d), -(v + 1)});
      r.pending = true;
      if constexpr (kResume) pending_vertices_.push_back(v);
    }
  }

  // The target in h's frame, unfolded to the side y > 0.
  // (Kept in h's record: an edge gets a few windows.)
  Vec2 target_in_frame(int h) {
    HalfedgeRecord& r = record(h);
    if (std::isnan(r.target_x)) {
      const HalfedgeFrame& f = frame_[h];
      const Vec3& a = mesh_.position(f.from);
      const Vec3 at = target_position_ - a;
      r.target_x = at.dot(mesh_.position(f.to) - a) / f.len;
      r.target_y = std::sqrt(std::max(0.0, at.squaredNorm() - r.target_x * r.target_x));
    }
    return {r.target_x, r.target_y};
  }

  // The queue's order: the A* bound while no length is known (the target is then reached
  // first), the distance from the source once one is (Dijkstra's order: a window is
  // propagated after the shorter windows that can cut it, so fewer are propagated in vain;
  // the bound against the best length still prunes the same windows).
  double order_key(int v, double d) const { return distance_order_ ? d : vertex_key(v, d); }

  double vertex_key(int v, double d) const {
    if (target_ < 0) return d;
    const double h = std::max((mesh_.position(v) - target_position_).norm(), landmark_bound(v));
    return d + (bound_ != nullptr ? std::max(h, bound_->at(v)) : h);
  }

  // Lights the edges opposite to v in its faces with v as the pseudo-source.
  // (d is v's current distance: the pending flag in run_leg() keeps stale events out.)
  void expand_vertex(int v, double d) {
    ++vertex_events_;
    const Vec3& pv = mesh_.position(v);
    outgoing_.clear();
    const int first = mesh_.vertex_halfedge(v);
    for (int o = first; o >= 0;) {
      outgoing_.push_back(o);
      o = mesh_.ccw_rotate(o);
      if (o == first) break;
    }
    const bool all = v == source_ || mesh_.is_boundary_vertex(v) || !continuation_range(v);
    for (std::size_t i = 0; i < outgoing_.size(); ++i) {
      const int o = outgoing_[i];
      relax(mesh_.to(o), d + mesh_.halfedge_length(o), -1, v);
      const int p = mesh_.prev(o);
      relax(mesh_.from(p), d + mesh_.halfedge_length(p), -1, v);
      if (!all && !continues_[i]) continue;
      const int h = mesh_.twin(mesh_.next(o));
      if (mesh_.is_boundary_halfedge(h)) continue;
      const Vec3& a = mesh_.position(mesh_.from(h));
      const Vec3& b = mesh_.position(mesh_.to(h));
      const double len = frame_[h].len;
      if (!(len > 0.0)) continue;
      const double x = (pv - a).dot(b - a) / len;
      const double y = -std::sqrt(std::max(0.0, (pv - a).squaredNorm() - x * x));
      add_window(make_window(h, 0.0, len, {x, y}, d, -(v + 1)));
    }
  }

  // A shortest path through the saddle v that arrived along direction u leaves it at an angle
  // >= pi from -u on both sides (otherwise a path around v would be shorter): only the faces
  // around v meeting that range need windows lit by v. Sets continues_ per outgoing_ entry;
  // false when the arrival direction is unknown (then every face is lit).
  bool continuation_range(int v) {
    const std::size_t n = outgoing_.size();
    corner_.resize(n + 1);
    corner_[0] = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      corner_[i + 1] = corner_[i] + window_mesh_.corner_angle[outgoing_[i]];
    const double total = corner_[n];
    // The angle, counter-clockwise from outgoing_[0], of the direction back along the arrival.
    double back = -1.0;
    const int pw = scratch_.vertices[v].provider_window;
    if (pw >= 0) {
      const int h = scratch_.arrivals[v].h;
      const Vec2 source = scratch_.arrivals[v].source;
      const int o = mesh_.prev(h);  // v -> from(h) in face(h)
      const double cx = frame_[h].cx, cy = frame_[h].cy;
      const Vec2 ca{-cx, -cy}, ci{source.x - cx, source.y - cy};
      const double beta = std::atan2(std::abs(cross(ca, ci)), dot(ca, ci));
      for (std::size_t i = 0; i < n; ++i)
        if (outgoing_[i] == o) back = corner_[i] + beta;
    } else {
      const int u = scratch_.vertices[v].provider_vertex;
      for (std::size_t i = 0; i < n; ++i)
        if (mesh_.to(outgoing_[i]) == u) back = corner_[i];
    }
    if (back < 0.0) return false;
    constexpr double kPi = 3.141592653589793, kTol = 1e-9;
    const double lo = kPi - kTol, hi = total - kPi + kTol;
    continues_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      double r0 = corner_[i] - back, r1 = corner_[i + 1] - back;
      if (r0 < 0.0) {
        r0 += total;
        r1 += total;
      }
      // [r0, r1] and its copy one turn down, against [lo, hi].
      continues_[i] = (r0 <= hi && r1 >= lo) || (r0 - total <= hi && r1 - total >= lo);
    }
    return true;
  }

  void add_window(Window w) {
    const double len = length(w);
    if (!(w.b1 - w.b0 > 1e-12 * len)) return;
    if (!trim(&w)) return;
    if (!compete(&w)) return;
    double order = 0.0, bound = 0.0;
    keys(w, &order, &bound);
    push_window(w, order, bound);
  }

  // The window's queue key (*order) and its lower bound of the paths to the target through it
  // (*bound, the A* bound), both its distance from the source in a full run.
  void keys(const Window& w, double* order, double* bound) {
    // The window's least distance from the source, computed only where it is used (the A*
    // order of a search to one target without landmarks needs none).
    const auto nearest = [&] {
      return w.sigma + norm(w.source - Vec2{std::clamp(w.source.x, w.b0, w.b1), 0.0});
    };
    if (target_ < 0) {
      *order = *bound = nearest();
      return;
    }
    // min over x in [b0, b1] of |I - (x, 0)| + |(x, 0) - t|: the target at its distance r
    // from the edge's line, unfolded to the other side (T = (tx, r)); the sum is convex in x
    // with its minimum where I -> T crosses the line.
    const double len = length(w);
    const Vec2 T = target_in_frame(w.h);
    const Vec2& I = w.source;
    const double cross_x = T.y - I.y > 0.0 ? I.x + (T.x - I.x) * (-I.y) / (T.y - I.y) : I.x;
    const double x = std::clamp(cross_x, w.b0, w.b1);
    const Vec2 X{x, 0.0};
    double key = w.sigma + norm(X - I) + norm(T - X);
    if (bound_ != nullptr) key = std::max(key, target_bound_key(w, len));
    if (landmarks_ != nullptr) {
      const double through = landmark_edge_bound(*landmarks_, target_landmark_.data(),
                                                 original_[frame_[w.h].from],
                                                 original_[frame_[w.h].to], len, w.b0, w.b1);
      key = std::max(key, nearest() + through);
    }
    *order = distance_order_ ? nearest() : key;
    *bound = key;
  }

  // min over x in [b0, b1] of sigma + |I x| + h(x), h the target bound, linear along the edge
  // (h(A) + s x): the sum is convex in x, its derivative (x - Ix) / |I x| + s vanishes at
  // x = Ix - s |Iy| / sqrt(1 - s^2) when |s| < 1 (otherwise the sum is monotone). -infinity
  // where h is not defined at both ends.
  double target_bound_key(const Window& w, double len) const {
    const HalfedgeFrame& f = frame_[w.h];
    const double ha = bound_->at(f.from), hb = bound_->at(f.to);
    if (!(ha > -std::numeric_limits<double>::infinity() &&
          hb > -std::numeric_limits<double>::infinity()))
      return -std::numeric_limits<double>::infinity();
    const Vec2& I = w.source;
    const double s = (hb - ha) / len;
    const double x = s >= 1.0    ? w.b0
                     : s <= -1.0 ? w.b1
                                 : std::clamp(I.x - s * std::abs(I.y) / std::sqrt(1.0 - s * s),
                                              w.b0, w.b1);
    return w.sigma + norm(Vec2{x, 0.0} - I) + ha + s * x;
  }

  // ALT lower bound on d(v, t): max over landmarks L of |d(L, t) - d(L, v)|.
  double landmark_bound(int v) const {
    if (landmarks_ == nullptr) return 0.0;
    const int k = landmarks_->count;
    const double* lv = landmarks_->dist.data() + static_cast<std::size_t>(original_[v]) * k;
    double bound = 0.0;
    for (int i = 0; i < k; ++i)
      bound = std::max({bound, target_landmark_[i] - lv[i], lv[i] - target_landmark_[i]});
    return std::isfinite(bound) ? bound : 0.0;
  }

  void push(const Event& e) { queue_.push(e); }

  // `order`: the queue key; `bound`: the A* bound against the best length.
  // (A resumable search keeps a window beyond the best length: it may serve a later target.)
  void push_window(const Window& w, double order, double bound) {
    if constexpr (!kResume) {
      if (!(bound < best_)) return;
    }
    int index = static_cast<int>(windows_.size());
    if (!free_.empty()) {
      index = free_.back();
      free_.pop_back();
      windows_[index] = w;
    } else {
      windows_.push_back(w);
    }
    int& first = insert_after_ >= 0 ? windows_[insert_after_].next : head(w.h);
    Window& x = windows_[index];
    x.next = first;
    first = index;
    x.bound = bound;
    schedule(w.h, order);
    ++created_;
    if (options_.max_windows > 0 && created_ > options_.max_windows) aborted_ = true;
  }

  // The queue holds halfedges, not windows: a halfedge's entry has the smallest key of the
  // windows queued on it since it last came out (lazily: a smaller key makes a new entry and
  // leaves the old one stale).
  void schedule(int h, double key) {
    // (h's record is this query's: push_window linked the window into h's list through
    // head(h), or after a window that compete found in it.)
    HalfedgeRecord& r = scratch_.halfedges[h];
    if (key < r.queued_key) {
      r.queued_key = key;
      push({key, h, ++r.tag});
    }
  }

  // A halfedge out of the queue propagates every window queued on it at once, in the order of
  // b0, whatever their keys (VTP's list at a time, Qin et al. 2016): the edge's frame, records
  // and windows are read while they are in cache, and its windows leave its list as they go.
  // (Keys order the work and never decide it: a window propagated before its turn is still a
  // real ray, and every window whose bound is below the best length is propagated before the
  // search stops. bench/README.md, session 12: 2-7 % more windows, 9-13 % less thread CPU per
  // path at the median, 16-25 % at the mean.) A cap on the windows (max_windows) is checked
  // between lists, so a search may end a list past it.
  // Windows whose bound reached the best length die here. Returns the number propagated.
  // Flattened: everything it calls (propagate, add_window, trim, compete and the window
  // intersection of window_distance.h) is inlined into this one loop; GCC's own choice had
  // left the intersection and, depending on the rest of the source, trim and Mesh::to out of
  // line (bench/README.md, session 13: 2.5 % fewer instructions, 10-14 % less time per path).
  [[gnu::flatten]] long propagate_list(const Event& e) {
    const int h = e.index;
    {
      HalfedgeRecord& r = scratch_.halfedges[h];
      if (r.tag != e.tag) return 0;  // stale (schedule made the record in this query)
      r.queued_key = std::numeric_limits<double>::infinity();
      ++r.tag;
    }
    long n = 0;
    if constexpr (kResume) {
      // Windows at or beyond the best length stay listed for later targets (retarget keys
      // them again).
      for (int prev = -1;;) {
        const int i = prev < 0 ? scratch_.halfedges[h].head : windows_[prev].next;
        if (i < 0) break;
        Window& o = windows_[i];
        if (!(o.bound < best_)) {
          prev = i;
          continue;
        }
        unlink(prev < 0 ? &scratch_.halfedges[h].head : &windows_[prev].next, o);
        propagate(i);
        ++n;
        free_.push_back(i);
      }
      return n;
    }
    // Each window leaves the list before it is propagated (its children lie on the two other
    // edges of face(h), whose lists are the only ones their competition touches). The head is
    // re-read every time: propagating pushes windows and may move the buffer.
    for (int i; (i = scratch_.halfedges[h].head) >= 0;) {
      Window& o = windows_[i];
      unlink(&scratch_.halfedges[h].head, o);
      if (!(o.bound < best_)) {
        if (recycle_) free_.push_back(i);
        continue;
      }
      propagate(i);
      ++n;
      if (recycle_) free_.push_back(i);
    }
    return n;
  }

  // Takes o, which *link names (the next of the window before it, or its halfedge's head), out
  // of its halfedge's list.
  static void unlink(int* link, Window& o) { *link = o.next; }

  // The endpoint vertices' distances along the edge against the window's: g_A(x) = d(A) + x -
  // (sigma + |I x|) has slope 1 - (slope of |I x|) >= 0, so A wins (g_A < 0) on a prefix of the
  // interval, and B likewise on a suffix. Cuts those parts off (a little less, for round-off);
  // false when nothing is left.
  bool trim(Window* w) const {
    const double len = length(*w), tol = 1e-12 * len;
    const Vec2 I = w->source;
    const double da = dist(frame_[w->h].from);
    if (da + w->b1 < w->sigma + norm(I - Vec2{w->b1, 0.0})) return false;
    if (da + w->b0 < w->sigma + norm(I - Vec2{w->b0, 0.0})) {
      // d(A) + x = sigma + |I x|, i.e. 2 x (k + sx) = sx^2 + sy^2 - k^2 with k = d(A) - sigma.
      const double k = da - w->sigma, den = 2.0 * (k + I.x);
      if (den > 0.0) w->b0 = std::max(w->b0, (I.x * I.x + I.y * I.y - k * k) / den - tol);
    }
    const double db = dist(frame_[w->h].to);
    if (db + (len - w->b0) < w->sigma + norm(I - Vec2{w->b0, 0.0})) return false;
    if (db + (len - w->b1) < w->sigma + norm(I - Vec2{w->b1, 0.0})) {
      const double k = db - w->sigma, sx = len - I.x, den = 2.0 * (k + sx);
      if (den > 0.0) w->b1 = std::min(w->b1, len - (sx * sx + I.y * I.y - k * k) / den + tol);
    }
    return w->b1 - w->b0 > tol;
  }

  double length(const Window& w) const { return frame_[w.h].len; }

  // h's record, initialised on its first use in the query.
  HalfedgeRecord& record(int h) {
    HalfedgeRecord& r = scratch_.halfedges[h];
    if (r.stamp != scratch_.stamp) {
      constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
      constexpr double kInf = std::numeric_limits<double>::infinity();
      r = HalfedgeRecord{scratch_.stamp, -1, kInf, 0.0, kNaN, kNaN, kInf, 0};
      if constexpr (kResume) touched_.push_back(h);
    }
    return r;
  }

  int& head(int h) { return record(h).head; }

  // The windows on an edge against each other (Mitchell, Mount and Papadimitriou's window
  // intersection, from the ends only): where another window on the same edge, lit from either
  // side, is shorter than w, every ray of w through that part is beaten there, hence beyond.
  // Cuts from w's ends what another window beats by more than round-off (a tie keeps both,
  // unless they are one window made twice), and cuts the queued windows the same way where w
  // beats them; a window left empty is dead. False when w is.
  bool compete(Window* w) {
    const double len = length(*w), tol = 1e-12 * len;
    insert_after_ = -1;
    return compete_side<true>(w, w->h, len, tol) &&
           compete_side<false>(w, frame_[w->h].twin, len, tol);
  }

  // compete against the windows listed on h: w's own halfedge (kSame), then its twin (its
  // windows are lit from the other side, their intervals mirrored in w's frame). One loop per
  // side: the walk along a list is the search's most frequent step.
  template <bool kSame>
  bool compete_side(Window* w, int h, double len, double tol) {
    HalfedgeRecord& r = scratch_.halfedges[h];
    if (r.stamp != scratch_.stamp) return true;
    int* link = &r.head;
    while (*link >= 0) {
      // (A list holds queued windows only: a window leaves it when it is propagated or dies.)
      Window& o = windows_[*link];
      // A halfedge's list is kept in the order of b0 (new windows are inserted there; a cut
      // may move a b0 up and leave the order a little off, which only costs a cut missed):
      // past w's end nothing overlaps it.
      if (kSame ? o.b0 >= w->b1 : o.b0 >= len - w->b0) break;
      // o in w's frame.
      const double ob0 = kSame ? o.b0 : len - o.b1, ob1 = kSame ? o.b1 : len - o.b0;
      const double lo = std::max(w->b0, ob0), hi = std::min(w->b1, ob1);
      if (hi - lo > tol) {
        const EdgeDistance wd{w->sigma, w->source.x, w->source.y};
        const EdgeDistance od{o.sigma, kSame ? o.source.x : len - o.source.x, o.source.y};
        const double eps = 1e-12 * (w->sigma + len);
        double c0 = ob0, c1 = ob1;  // o, in w's frame
        cut_overlap(wd, od, lo, hi, eps, tol, &w->b0, &w->b1, &c0, &c1);
        if (!(w->b1 - w->b0 > tol)) return false;
        if (!(c1 - c0 > tol)) {  // o is beaten: it leaves the list
          if (recycle_) free_.push_back(*link);
          unlink(link, o);
          continue;
        }
        o.b0 = kSame ? c0 : len - c1;
        o.b1 = kSame ? c1 : len - c0;
      }
      if (kSame && o.b0 <= w->b0) insert_after_ = *link;
      link = &o.next;
    }
    return true;
  }

  // (Called once per window: propagate_list has taken it out of its list.)
  void propagate(int index) {
    Window w = windows_[index];
    const int h = w.h;
    const double len = length(w);
    if (!trim(&w)) return;
    const HalfedgeFrame& f = frame_[h];
    const int c = f.opposite;
    const double cx = f.cx, cy = f.cy;
    if (!(cy > 0.0)) return;  // degenerate face
    // What its children and the vertex it reaches name as their parent: its record (the middle
    // of its interval as it was queued, before the trim), or, in a full run with reused slots,
    // its slot.
    int me = index;
    if constexpr (!kReuse) {
      const Window& q = windows_[index];
      me = static_cast<int>(records_.size());
      records_.push_back({h, q.parent, 0.5 * (q.b0 + q.b1)});
    }
    const Vec2 A{0.0, 0.0}, B{len, 0.0}, C{cx, cy}, I = w.source;
    // The ray from I through C meets the edge at xc.
    const double xc = I.x + (cx - I.x) * (-I.y) / (cy - I.y);
    const double tol = 1e-12 * len;
    // One angle, one split: when a ray through another window on h reached C more cheaply
    // (crossing h at x*), the rays of this window that cross the segment x* -> C are beaten at
    // the crossing point (there d_w >= d_w(C) - |PC| > d*(C) - |PC| = d*), hence beyond it: a
    // child on the far side of that segment keeps only the part whose rays do not cross it.
    double keep_left = w.b1, keep_right = w.b0;  // left child within x <= keep_left, ...
    const double dc = w.sigma + norm(C - I);
    HalfedgeRecord& r = record(h);
    if (dc > r.split_dist) {
      const double xs = r.split_x;
      if (xc < xs) keep_right = xs;  // rays in (xc, xs) cross x* -> C to reach C -> B
      if (xc > xs) keep_left = xs;   // rays in (xs, xc) cross it to reach A -> C
    }
    if (xc >= w.b0 - tol && xc <= w.b1 + tol) {
      // This window's ray reaches C: a real path (dc of a window whose cone misses C is no
      // path, but it still bounds that window's distances on the segment x* -> C above).
      relax(c, dc, me, -1, h, I);
      if (dc < r.split_dist) {
        r.split_dist = dc;
        r.split_x = xc;
      }
    }
    const double lac = f.len_prev, lcb = f.len_next;
    // Rays through [b0, min(b1, xc)] leave through A -> C: the child on twin(prev(h)), frame A.
    if (w.b0 < std::min(xc, keep_left)) {
      const int g = f.out_prev;
      if (g >= 0) {
        const double hi = std::min({w.b1, xc, keep_left});
        const double s0 = std::clamp(ray_hit(I, {w.b0, 0.0}, A, C), 0.0, 1.0);
        const double s1 = hi >= xc ? 1.0 : std::clamp(ray_hit(I, {hi, 0.0}, A, C), 0.0, 1.0);
        const Vec2 e{cx / lac, cy / lac};
        // ICH's third check: B beats the child at its end nearest A, hence everywhere on it
        // (moving towards C, the ray from I turns towards A -> C no less than the line from B).
        const Vec2 p0{s0 * cx, s0 * cy};
        const bool beaten = dist(f.to) + norm(p0 - B) < w.sigma + norm(p0 - I);
        if (s1 > s0 && !beaten)
          add_window(make_window(g, s0 * lac, s1 * lac, {dot(I, e), cross(e, I)}, w.sigma, me));
      }
    }
    // Rays through [max(b0, xc), b1] leave through C -> B: the child on twin(next(h)), frame C.
    if (w.b1 > std::max(xc, keep_right)) {
      const int g = f.out_next;
      if (g >= 0) {
        const double lo = std::max({w.b0, xc, keep_right});
        const double s0 = lo <= xc ? 0.0 : std::clamp(ray_hit(I, {lo, 0.0}, C, B), 0.0, 1.0);
        const double s1 = std::clamp(ray_hit(I, {w.b1, 0.0}, C, B), 0.0, 1.0);
        const Vec2 e{(len - cx) / lcb, -cy / lcb};
        const Vec2 r = I - C;
        // The same with A at the child's end nearest B.
        const Vec2 p1{cx + s1 * (len - cx), cy - s1 * cy};
        const bool beaten = dist(f.from) + norm(p1 - A) < w.sigma + norm(p1 - I);
        if (s1 > s0 && !beaten)
          add_window(make_window(g, s0 * lcb, s1 * lcb, {dot(r, e), cross(e, r)}, w.sigma, me));
      }
    }
  }

  // The legs between the pseudo-sources the path passes, from the providers back from the
  // target, joined at those vertices.
  bool build_path(SurfacePath* path, std::vector<int>* passed) const {
    std::vector<SurfacePath> legs;
    std::vector<int> joints;
    int u = target_;
    for (int guard = 0; u != source_; ++guard) {
      if (guard > mesh_.num_vertices()) return false;
      SurfacePath leg;
      leg.end = SurfacePoint::at_vertex(u);
      int v = -1;
      if (scratch_.vertices[u].provider_window >= 0) {
        std::vector<int> chain;
        for (int w = scratch_.vertices[u].provider_window; w >= 0; w = records_[w].parent)
          chain.push_back(w);
        std::reverse(chain.begin(), chain.end());
        v = -(records_[chain.front()].parent + 1);
        for (const int w : chain) {
          leg.halfedges.push_back(mesh_.twin(records_[w].h));
          leg.lambdas.push_back(
              std::clamp(1.0 - records_[w].mid / frame_[records_[w].h].len, 0.0, 1.0));
        }
        leg.start_face = mesh_.face(leg.halfedges.front());
      } else {
        v = scratch_.vertices[u].provider_vertex;
        if (v < 0) return false;
        for (const int o : mesh_.outgoing_halfedges(v)) {
          if (mesh_.to(o) == u || mesh_.from(mesh_.prev(o)) == u) {
            leg.start_face = mesh_.face(o);
            break;
          }
        }
        if (leg.start_face < 0) return false;
      }
      leg.start = SurfacePoint::at_vertex(v);
      legs.push_back(std::move(leg));
      if (v != source_) joints.push_back(v);
      u = v;
    }
    if (legs.empty()) return false;
    std::reverse(legs.begin(), legs.end());
    std::reverse(joints.begin(), joints.end());
    SurfacePath joined = legs.front();
    for (std::size_t i = 1; i < legs.size(); ++i) {
      joined = join_at_vertex(mesh_, joined, legs[i], joints[i - 1]);
      if (joined.start_face < 0) return false;
    }
    *path = std::move(joined);
    *passed = std::move(joints);
    return true;
  }

  const WindowMesh& window_mesh_;
  const Mesh& mesh_;     // the renumbered copy
  const int* original_;  // its vertex -> the original vertex
  const std::vector<char>& pseudo_;
  const HalfedgeFrame* frame_;
  const int source_;
  int target_;  // (a resumable search's changes)
  const WindowSearchOptions options_;
  Vec3 target_position_;
  const Landmarks* landmarks_;
  std::vector<double> target_landmark_;
  const TargetBound* bound_ = nullptr;  // the target bound, when built and active
  Scratch& scratch_;
  std::vector<Window>& windows_;
  // (Written by every search but a full run with reused slots; a full run without reuse writes
  // them unread.)
  std::vector<PathRecord>& records_;
  RadixQueue<Event>& queue_;
  std::vector<int>& outgoing_;
  std::vector<double> corner_;
  std::vector<char> continues_;
  double best_;
  int insert_after_ = -1;  // compete's place for w in its halfedge's list (-1: the head)
  bool distance_order_;  // (set again when the bound brings a straightened length)
  // Windows propagated or dead give their slots to later ones (free_), so that only the
  // wavefront stays in memory (bench/README.md, session 11: 13.6M windows made by a full run at
  // 300K faces, a few 10K alive at a time; session 14: 1-3 % of a search to a target's): a full
  // run with reused slots and every search to a target, whose path is built back through
  // PathRecords (a full run without reuse keeps every slot).
  const bool recycle_;
  std::vector<int> free_;
  long created_ = 0;
  long vertex_events_ = 0;
  bool aborted_ = false;
  // (kResume) Halfedges with a record in this search, and vertices given an event (with
  // repeats): what retarget keys again.
  std::vector<int> touched_;
  std::vector<int> pending_vertices_;
};

}  // namespace window_search
}  // namespace windplan
