#include "geometry/mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

std::string tri_str(const Tri& t) {
  std::ostringstream s;
  s << "(" << t[0] << ", " << t[1] << ", " << t[2] << ")";
  return s.str();
}

}  // namespace

Mesh::Mesh(TriangleSoup soup) : points_(std::move(soup.points)), tris_(std::move(soup.triangles)) {
  const int nv = num_vertices();
  const int nf = num_faces();
  const int nh = 3 * nf;

  for (int f = 0; f < nf; ++f) {
    const Tri& t = tris_[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= nv) {
        throw TopologyError("triangle " + std::to_string(f) + " " + tri_str(t) +
                            " has a vertex index out of range [0, " + std::to_string(nv) + ")");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      throw TopologyError("triangle " + std::to_string(f) + " " + tri_str(t) +
                          " repeats a vertex index");
    }
  }

  corners_.resize(nh);
  for (int h = 0; h < nh; ++h) corners_[h] = tris_[h / 3][h % 3];

  // Outgoing interior halfedges per vertex in CSR form (counting sort by from-vertex). Twins are
  // then found by scanning the short outgoing list of the head vertex: O(sum of degree^2), which
  // is linear for bounded degree and needs no hashing.
  std::vector<int> start(nv + 1, 0);
  for (const Tri& t : tris_)
    for (int k = 0; k < 3; ++k) ++start[t[k] + 1];
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> out(nh);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int h = 0; h < nh; ++h) out[fill[interior_from(h)]++] = h;
  }

  twin_.assign(nh, -1);
  for (int h = 0; h < nh; ++h) {
    if (twin_[h] >= 0) continue;
    const int a = interior_from(h);
    const int b = interior_to(h);
    int match = -1;
    for (int i = start[b]; i < start[b + 1]; ++i) {
      const int g = out[i];
      const int gb = interior_to(g);
      if (gb != a) continue;
      if (match >= 0) {
        throw TopologyError("edge (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") is shared by more than two triangles (non-manifold edge), e.g. " +
                            "triangles " + std::to_string(match / 3) + " and " +
                            std::to_string(g / 3));
      }
      match = g;
    }
    // The same directed edge twice means either a non-manifold edge or flipped orientation.
    for (int i = start[a]; i < start[a + 1]; ++i) {
      const int g = out[i];
      if (g == h) continue;
      const int gb = interior_to(g);
      if (gb == b) {
        throw TopologyError("directed edge (" + std::to_string(a) + " -> " + std::to_string(b) +
                            ") appears in triangles " + std::to_string(h / 3) + " and " +
                            std::to_string(g / 3) +
                            " (inconsistent orientation or non-manifold edge)");
      }
    }
    if (match >= 0) {
      if (twin_[match] >= 0) {
        throw TopologyError("edge (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") is shared by more than two triangles (non-manifold edge)");
      }
      twin_[h] = match;
      twin_[match] = h;
    }
  }

  // Boundary halfedges: one per interior halfedge without a twin, running the other way.
  std::vector<int> boundary_out(nv, -1);  // outgoing boundary halfedge per vertex
  for (int h = 0; h < nh; ++h) {
    if (twin_[h] >= 0) continue;
    const int b = static_cast<int>(twin_.size());
    twin_.push_back(h);
    twin_[h] = b;
    const int tail = interior_to(h);  // boundary runs to(h) -> from(h)
    if (boundary_out[tail] >= 0) {
      throw TopologyError("vertex " + std::to_string(tail) +
                          " is non-manifold (two boundary fans meet there)");
    }
    boundary_out[tail] = b;
  }
  const int nb = static_cast<int>(twin_.size()) - nh;
  bnext_.assign(nb, -1);
  bprev_.assign(nb, -1);
  for (int i = 0; i < nb; ++i) {
    const int b = nh + i;
    const int head = from(twin_[b]);
    const int n = boundary_out[head];
    bnext_[i] = n;
    bprev_[n - nh] = b;
  }

  // Edges: one per twin pair, represented by its interior (lower) halfedge.
  edge_.assign(twin_.size(), -1);
  edge_halfedge_.clear();
  edge_halfedge_.reserve(nh / 2 + nb);
  for (int h = 0; h < nh; ++h) {
    if (edge_[h] >= 0) continue;
    const int e = static_cast<int>(edge_halfedge_.size());
    edge_halfedge_.push_back(h);
    edge_[h] = e;
    edge_[twin_[h]] = e;
  }

  // Vertex halfedges: the most clockwise outgoing interior halfedge.
  vertex_halfedge_.assign(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (start[v] == start[v + 1]) continue;
    if (boundary_out[v] >= 0) {
      // Interior halfedge out of v whose twin is boundary: the twin of the boundary halfedge
      // arriving at v.
      const int bin = bprev_[boundary_out[v] - nh];
      vertex_halfedge_[v] = twin_[bin];
    } else {
      vertex_halfedge_[v] = out[start[v]];
    }
    // Manifold check: the fan from vertex_halfedge must reach every outgoing halfedge.
    int count = 0;
    int h = vertex_halfedge_[v];
    const int first = h;
    do {
      ++count;
      h = ccw_rotate(h);
    } while (h >= 0 && h != first && count <= start[v + 1] - start[v]);
    if (count != start[v + 1] - start[v]) {
      throw TopologyError("vertex " + std::to_string(v) +
                          " is non-manifold (its triangles form more than one fan)");
    }
  }
}

void Mesh::set_points(std::vector<Vec3> points) {
  if (points.size() != points_.size()) {
    throw InvariantError("Mesh::set_points: vertex count changed");
  }
  points_ = std::move(points);
}

std::vector<int> Mesh::outgoing_halfedges(int v) const {
  std::vector<int> result;
  const int first = vertex_halfedge_[v];
  if (first < 0) return result;
  int h = first;
  do {
    result.push_back(h);
    h = ccw_rotate(h);
  } while (h >= 0 && h != first);
  return result;
}

int Mesh::valence(int v) const {
  const int first = vertex_halfedge_[v];
  if (first < 0) return 0;
  int n = 0;
  int h = first;
  do {
    ++n;
    h = ccw_rotate(h);
  } while (h >= 0 && h != first);
  return is_boundary_vertex(v) ? n + 1 : n;
}

double Mesh::edge_length(int e) const { return halfedge_length(edge_halfedge_[e]); }

Vec3 Mesh::face_area_vector(int f) const {
  const Tri& t = tris_[f];
  return 0.5 * (points_[t[1]] - points_[t[0]]).cross(points_[t[2]] - points_[t[0]]);
}

Vec3 Mesh::face_normal(int f) const {
  const Vec3 a = face_area_vector(f);
  const double n = a.norm();
  return n > 0.0 ? Vec3(a / n) : Vec3::Zero();
}

double Mesh::face_area(int f) const { return face_area_vector(f).norm(); }

Vec3 Mesh::face_centroid(int f) const {
  const Tri& t = tris_[f];
  return (points_[t[0]] + points_[t[1]] + points_[t[2]]) / 3.0;
}

double Mesh::corner_angle(int h) const {
  const Vec3& p = position(from(h));
  const Vec3 u = position(to(h)) - p;
  const Vec3 w = position(from(prev(h))) - p;
  // atan2 of |u x w| and u.w is accurate for all angles, unlike acos.
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

double Mesh::cone_angle(int v) const {
  double sum = 0.0;
  const int first = vertex_halfedge_[v];
  if (first < 0) return 0.0;
  int h = first;
  do {
    sum += corner_angle(h);
    h = ccw_rotate(h);
  } while (h >= 0 && h != first);
  return sum;
}

VertexType Mesh::vertex_type(int v, double tol) const {
  if (vertex_halfedge_[v] < 0) return VertexType::Isolated;
  if (is_boundary_vertex(v)) return VertexType::Boundary;
  const double a = cone_angle(v);
  const double two_pi = 2.0 * M_PI;
  if (a < two_pi - tol) return VertexType::Spherical;
  if (a > two_pi + tol) return VertexType::Saddle;
  return VertexType::Euclidean;
}

Vec3 Mesh::vertex_normal(int v) const {
  Vec3 n = Vec3::Zero();
  const int first = vertex_halfedge_[v];
  if (first < 0) return n;
  int h = first;
  do {
    n += corner_angle(h) * face_normal(face(h));
    h = ccw_rotate(h);
  } while (h >= 0 && h != first);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : n;
}

double Mesh::total_area() const {
  double a = 0.0;
  for (int f = 0; f < num_faces(); ++f) a += face_area(f);
  return a;
}

BoundingBox Mesh::bounding_box() const {
  BoundingBox box;
  if (points_.empty()) return box;
  box.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  box.max = -box.min;
  for (const Vec3& p : points_) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

std::array<double, 3> Mesh::edge_length_stats() const {
  if (num_edges() == 0) return {0.0, 0.0, 0.0};
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0, sum = 0.0;
  for (int e = 0; e < num_edges(); ++e) {
    const double l = edge_length(e);
    lo = std::min(lo, l);
    hi = std::max(hi, l);
    sum += l;
  }
  return {lo, sum / num_edges(), hi};
}

std::vector<int> Mesh::face_components(int* count) const {
  const int nf = num_faces();
  std::vector<int> comp(nf, -1);
  std::vector<int> stack;
  int c = 0;
  for (int seed = 0; seed < nf; ++seed) {
    if (comp[seed] >= 0) continue;
    comp[seed] = c;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int g = face(twin_[3 * f + k]);
        if (g >= 0 && comp[g] < 0) {
          comp[g] = c;
          stack.push_back(g);
        }
      }
    }
    ++c;
  }
  if (count) *count = c;
  return comp;
}

int Mesh::num_components() const {
  int c = 0;
  face_components(&c);
  return c;
}

int Mesh::num_unreferenced_vertices() const {
  return static_cast<int>(std::count(vertex_halfedge_.begin(), vertex_halfedge_.end(), -1));
}

int Mesh::euler_characteristic() const {
  return (num_vertices() - num_unreferenced_vertices()) - num_edges() + num_faces();
}

int Mesh::genus() const {
  if (num_components() != 1) return -1;
  const int b = static_cast<int>(boundary_loops().size());
  return (2 - euler_characteristic() - b) / 2;
}

std::vector<std::vector<int>> Mesh::boundary_loops() const {
  std::vector<std::vector<int>> loops;
  const int nh = num_interior_halfedges();
  std::vector<char> seen(num_boundary_halfedges(), 0);
  for (int i = 0; i < num_boundary_halfedges(); ++i) {
    if (seen[i]) continue;
    std::vector<int> loop;
    int b = nh + i;
    while (!seen[b - nh]) {
      seen[b - nh] = 1;
      loop.push_back(b);
      b = next(b);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::vector<int> Mesh::loop_vertices(const std::vector<int>& loop) const {
  std::vector<int> vs;
  vs.reserve(loop.size());
  for (int h : loop) vs.push_back(from(h));
  return vs;
}

}  // namespace windplan
