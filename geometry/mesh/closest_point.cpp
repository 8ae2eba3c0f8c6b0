#include "geometry/mesh/closest_point.h"

#include <algorithm>
#include <limits>

namespace windplan {

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                               Vec3* bary) {
  // Ericson, Real-Time Collision Detection, 5.1.5: Voronoi regions of the triangle.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    *bary = Vec3(1, 0, 0);
    return a;
  }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) {
    *bary = Vec3(0, 1, 0);
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    *bary = Vec3(1 - v, v, 0);
    return a + v * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) {
    *bary = Vec3(0, 0, 1);
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    *bary = Vec3(1 - w, 0, w);
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    *bary = Vec3(0, 1 - w, w);
    return b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  *bary = Vec3(1 - v - w, v, w);
  return a + ab * v + ac * w;
}

ClosestPointQuery::ClosestPointQuery(const Mesh& mesh) : mesh_(mesh) {
  const int nf = mesh.num_faces();
  order_.resize(nf);
  centroid_.resize(nf);
  for (int f = 0; f < nf; ++f) {
    order_[f] = f;
    centroid_[f] = mesh.face_centroid(f);
  }
  nodes_.reserve(2 * static_cast<std::size_t>(nf / 4 + 1));
  if (nf > 0) build(0, nf);
  // The leaves' corners side by side in the hierarchy's order: a leaf reads one stretch of
  // memory instead of three vertex records per face at random places.
  corners_.resize(3 * static_cast<std::size_t>(nf));
  for (int i = 0; i < nf; ++i) {
    const Tri& t = mesh.triangle(order_[i]);
    for (int k = 0; k < 3; ++k) corners_[3 * static_cast<std::size_t>(i) + k] = mesh.position(t[k]);
  }
}

int ClosestPointQuery::build(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = begin; i < end; ++i) {
    const Tri& t = mesh_.triangle(order_[i]);
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(mesh_.position(t[k]));
      hi = hi.cwiseMax(mesh_.position(t[k]));
    }
  }
  nodes_[id].lo = lo;
  nodes_[id].hi = hi;
  if (end - begin <= 4) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return id;
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int a, int b) { return centroid_[a][axis] < centroid_[b][axis]; });
  const int l = build(begin, mid);
  const int r = build(mid, end);
  nodes_[id].left = l;
  nodes_[id].right = r;
  return id;
}

ClosestPointQuery::Hit ClosestPointQuery::closest(const Vec3& q) const {
  return closest_within(q, std::numeric_limits<double>::infinity());
}

ClosestPointQuery::Hit ClosestPointQuery::closest_within(const Vec3& q, double bound2) const {
  Hit best;
  best.distance = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  double best2 = bound2;
  auto box_dist2 = [&](const Node& n) {
    const Vec3 d = (n.lo - q).cwiseMax(q - n.hi).cwiseMax(Vec3::Zero());
    return d.squaredNorm();
  };
  // Nodes to visit with their boxes' squared distances (computed once, when pushed). The
  // median split keeps the depth near log2(F / 4), and the stack holds at most one node per
  // level beside the path down.
  struct Entry {
    int id;
    double dist2;
  };
  Entry stack[2 * kMaxDepth];
  int top = 0;
  stack[top++] = {0, box_dist2(nodes_[0])};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.dist2 >= best2) continue;
    const Node& n = nodes_[e.id];
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const Vec3* t = &corners_[3 * static_cast<std::size_t>(i)];
        Vec3 b;
        const Vec3 c = closest_point_on_triangle(q, t[0], t[1], t[2], &b);
        const double d2 = (c - q).squaredNorm();
        if (d2 < best2) {
          best2 = d2;
          best.point = SurfacePoint::in_face(order_[i], b);
          best.position = c;
        }
      }
    } else {
      const double dl = box_dist2(nodes_[n.left]), dr = box_dist2(nodes_[n.right]);
      if (dl < dr) {
        stack[top++] = {n.right, dr};
        stack[top++] = {n.left, dl};
      } else {
        stack[top++] = {n.left, dl};
        stack[top++] = {n.right, dr};
      }
    }
  }
  if (best.point.element >= 0) best.distance = std::sqrt(best2);
  return best;
}

}  // namespace windplan
