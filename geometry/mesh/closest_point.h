#pragma once
// Closest point on a triangle mesh: a bounding-volume hierarchy over the faces (median split),
// built once (precompute) and queried many times.
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

class ClosestPointQuery {
 public:
  /// Builds the hierarchy in O(F log F). The mesh must outlive the query object.
  explicit ClosestPointQuery(const Mesh& mesh);

  struct Hit {
    SurfacePoint point;  ///< Face point (barycentric) of the closest point
    Vec3 position;
    double distance = 0.0;  ///< mm
  };
  /// The closest surface point to q. An empty mesh gives distance = +inf and point.element -1.
  Hit closest(const Vec3& q) const;
  /// The closest surface point to q among those strictly nearer than sqrt(bound2) (mm^2): when
  /// there is one, the same hit as closest(q) (it visits a subset of closest(q)'s nodes in the
  /// same order, pruning more of them); otherwise distance = +inf and point.element -1. For a minimum over
  /// many points, whose far ones are then rejected near the tree's root.
  Hit closest_within(const Vec3& q, double bound2) const;

 private:
  struct Node {
    Vec3 lo, hi;
    int left = -1, right = -1;  // children, or -1 for a leaf
    int begin = 0, end = 0;     // face range in order_ for leaves
  };
  int build(int begin, int end);
  /// Deepest hierarchy: a median split of leaves of <= 4 faces stays far below it.
  static constexpr int kMaxDepth = 64;
  const Mesh& mesh_;
  std::vector<int> order_;
  std::vector<Vec3> corners_;  ///< 3 per face, in order_'s order
  std::vector<Node> nodes_;
  std::vector<Vec3> centroid_;
};

/// Closest point of triangle (a, b, c) to p; writes barycentric coordinates.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                               Vec3* bary);

}  // namespace windplan
