#pragma once
// The girth field of a winding surface (issue 5).
//
// The girth g(p) at a point p of an annulus (the wound region of a mandrel, geometry/
// winding_surface.h) is the length of the shortest closed curve through p that winds once around
// the annulus: a p-constrained geodesic loop, geodesic everywhere except for a corner allowed at
// p. It bounds what a circuit through p can do (a hoop through p is never shorter than g(p)) and
// it is 2-Lipschitz: |g(p) - g(q)| <= 2 d(p, q) (go from q to p, around p's loop, and back).
//
// Exact evaluation (girth_at): the annulus is cut along a seam, a shortest edge path from
// boundary loop 0 to boundary loop 1. The vertex graph is lifted to its double cover across the
// seam (an edge that crosses the seam switches copies); the shortest edge path from (p, copy 0)
// to (p, copy 1) is the shortest edge loop through p that crosses the seam an odd number of
// times. Its face strip, opened at p, is refined by the geodesic core
// (geometry/geodesic/geodesic.h) as an open path from p to p with both ends fixed; the refined
// loop's winding number (net signed seam crossings of its closed face strip) is checked to be +-1.
//
// The field (compute_girth_field): g is evaluated exactly at `samples` vertices, placed on rings
// of an intrinsic axial coordinate t = d0 / (d0 + d1) (d0, d1: edge-graph distances to the two
// boundary loops; stations include both loops) or by farthest-point sampling under the
// edge-graph distance. The exact loops are independent and run on the hardware threads. Every
// other vertex gets a weighted linear least-squares fit g ~ a + b (t_i - t) over its k = 8
// nearest samples by edge-graph distance (one Dijkstra carrying k + 1 labels per vertex), with
// modified-Shepard (Franke-Little) weights w_i = ((R - d_i) / (R d_i))^2, R the distance of the
// (k+1)-th nearest sample: local, continuous, exact at the samples, exact for g linear in t (a
// cone) and needing no spindle axis (bent tubes). The value is clamped into the intersection of
// the samples' Lipschitz intervals [g_i - 2 d_i, g_i + 2 d_i], so it never contradicts them.
//
// Distances are edge-graph (Dijkstra) distances, which are >= the geodesic distances, so
// lipschitz_bound is a conservative (valid) bound on |g - g_nearest sample|.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

struct GirthOptions {
  int samples = 64;  ///< sample points where g is computed exactly (count, >= 4)
  std::string placement =
      "rings";  ///< "rings": rings of stations along the axis; "farthest": farthest-point sampling
  int rings = 0;  ///< for "rings": stations along the axis (0: auto ~ sqrt(samples))
  bool is_valid(std::string* why) const;
};

struct GirthSample {
  int vertex;     ///< winding-surface vertex
  double girth;   ///< exact g at the vertex (mm)
  Vec3 position;  ///< the vertex's position (mm)
};

struct GirthField {
  std::vector<double> vertex_girth;  ///< per winding-surface vertex (mm), interpolated
  std::vector<GirthSample> samples;  ///< exact evaluations
  double lipschitz_bound =
      0.0;  ///< max over vertices of 2 * d(vertex, nearest sample) (mm): |g(p)-g(q)| <= 2 d(p,q)
  double time_ms = 0.0;
  /// Diagnostics: samples whose refined loop did not converge or did not wind exactly once
  /// (their value is still the length of the best loop found).
  int unconverged_samples = 0;
  std::vector<double> face_girth(const Mesh& mesh) const;  ///< per face: mean of its vertices
};

/// Exact girth at one surface vertex: the shortest loop through p winding once around the annulus.
/// \param annulus a single-component mesh with exactly two boundary loops, genus 0
/// \param loops the two boundary loops as vertex index lists (e.g.
/// Mandrel::winding.loops[i].vertices) \param vertex the vertex p, in [0, #V) \param loop_out when
/// given, receives the refined loop as an open SurfacePath from p to p \return g(p) (mm) \throw
/// TopologyError when the mesh is not an annulus (naming its number of boundary loops and
///        components); InputError for a vertex out of range or loops that are not the mesh's
///        boundary loops.
double girth_at(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops, int vertex,
                SurfacePath* loop_out = nullptr);

/// The girth field: exact samples, interpolation to every vertex, sampling error bound, time.
/// \throw ConfigError for invalid options; TopologyError/InputError as girth_at.
GirthField compute_girth_field(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops,
                               const GirthOptions& = {});

/// Precompute / query split for many exact evaluations on one annulus (girth_at builds one of
/// these per call): the edge graph, the seam and the seam-lifted graph.
class GirthContext {
 public:
  /// \throw as girth_at.
  GirthContext(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops);
  ~GirthContext();
  GirthContext(const GirthContext&) = delete;
  GirthContext& operator=(const GirthContext&) = delete;

  struct Loop {
    double girth = 0.0;        ///< refined loop length (mm)
    double edge_length = 0.0;  ///< length of the initial edge loop (mm)
    int winding = 0;           ///< net signed seam crossings of the refined loop (+-1 expected)
    bool converged = false;    ///< the geodesic refinement converged (see summary)
    SurfacePath path;          ///< open path from p to p
    GeodesicSummary summary;   ///< the refinement's summary
    bool retried = false;      ///< the first refinement failed and was retried without funnel start
  };
  /// Exact girth at vertex p. When `distances` is given, it receives the edge-graph distance
  /// from p to every vertex (the lifted search then runs to completion).
  Loop girth(int vertex, std::vector<double>* distances = nullptr) const;

  /// The initial loop through vertex p (before refinement): the shortest edge loop through p
  /// crossing the seam an odd number of times, as an open strip from p to p. `edge_length`
  /// receives its edge-graph length (mm); `distances` as in girth(); `cycle` the edge loop's
  /// vertices p, v_1, ..., v_{m-1} (p not repeated).
  SurfacePath initial_loop(int vertex, double* edge_length = nullptr,
                           std::vector<double>* distances = nullptr,
                           std::vector<int>* cycle = nullptr) const;
  /// The seam: vertex path from loop 0 to loop 1.
  const std::vector<int>& seam() const;
  /// Net signed seam crossings of a closed face chain: the path's strip, closed at its start
  /// vertex by a rotation around it.
  int winding_number(const SurfacePath& path) const;
  const Mesh& mesh() const { return mesh_; }

 private:
  // The loop refined as two open halves p -> q -> p joined at q (empty on failure).
  SurfacePath refined_halves(int p, const std::vector<int>& cycle) const;
  struct Impl;
  const Mesh& mesh_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace windplan
