// Morton-order renumbering of a mesh (see geometry/mesh/mesh_order.h).
#include "geometry/mesh/mesh_order.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace windplan {

namespace {

// The 21 low bits of x spread to every third bit.
std::uint64_t spread(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

int MeshOrder::halfedge_from_local(const Mesh& original, int h) const {
  if (!mesh.is_boundary_halfedge(h)) return 3 * face_from_local[h / 3] + h % 3;
  return original.twin(halfedge_from_local(original, mesh.twin(h)));
}

SurfacePoint MeshOrder::point_from_local(const Mesh& original, const SurfacePoint& p) const {
  SurfacePoint q = p;
  if (p.element < 0) return q;
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      q.element = vertex_from_local[p.element];
      break;
    case SurfacePoint::Kind::Edge:
      q.element = halfedge_from_local(original, p.element);
      break;
    case SurfacePoint::Kind::Face:
      q.element = face_from_local[p.element];
      break;
  }
  return q;
}

SurfacePath MeshOrder::path_from_local(const Mesh& original, const SurfacePath& path) const {
  SurfacePath q = path;
  q.start = point_from_local(original, path.start);
  q.end = point_from_local(original, path.end);
  if (path.start_face >= 0) q.start_face = face_from_local[path.start_face];
  for (int& h : q.halfedges) h = halfedge_from_local(original, h);
  return q;
}

MeshOrder order_for_locality(const Mesh& mesh) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  // Morton codes of the positions quantised to 2^21 steps per axis of the bounding box.
  const BoundingBox box = mesh.bounding_box();
  const Vec3 size = box.diagonal();
  std::vector<std::uint64_t> code(nv);
  for (int v = 0; v < nv; ++v) {
    std::uint64_t c = 0;
    for (int a = 0; a < 3; ++a) {
      double t = size[a] > 0.0 ? (mesh.position(v)[a] - box.min[a]) / size[a] : 0.0;
      if (!(t >= 0.0)) t = 0.0;  // (NaN too: a mesh built in code; readers refuse them)
      const auto q = static_cast<std::uint64_t>(std::min(t, 1.0) * 2097151.0);
      c |= spread(q) << a;
    }
    code[v] = c;
  }
  MeshOrder o;
  o.vertex_from_local.resize(nv);
  std::iota(o.vertex_from_local.begin(), o.vertex_from_local.end(), 0);
  std::sort(o.vertex_from_local.begin(), o.vertex_from_local.end(),
            [&](int a, int b) { return code[a] != code[b] ? code[a] < code[b] : a < b; });
  o.vertex_to_local.resize(nv);
  for (int i = 0; i < nv; ++i) o.vertex_to_local[o.vertex_from_local[i]] = i;

  std::vector<int> first(nf);
  for (int f = 0; f < nf; ++f) {
    const Tri& t = mesh.triangle(f);
    first[f] =
        std::min({o.vertex_to_local[t[0]], o.vertex_to_local[t[1]], o.vertex_to_local[t[2]]});
  }
  o.face_from_local.resize(nf);
  std::iota(o.face_from_local.begin(), o.face_from_local.end(), 0);
  std::sort(o.face_from_local.begin(), o.face_from_local.end(),
            [&](int a, int b) { return first[a] != first[b] ? first[a] < first[b] : a < b; });

  TriangleSoup soup;
  soup.points.resize(nv);
  for (int i = 0; i < nv; ++i) soup.points[i] = mesh.position(o.vertex_from_local[i]);
  soup.triangles.resize(nf);
  for (int i = 0; i < nf; ++i) {
    const Tri& t = mesh.triangle(o.face_from_local[i]);
    soup.triangles[i] = {o.vertex_to_local[t[0]], o.vertex_to_local[t[1]], o.vertex_to_local[t[2]]};
  }
  o.mesh = Mesh(std::move(soup));
  return o;
}

}  // namespace windplan
