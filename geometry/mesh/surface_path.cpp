#include "geometry/mesh/surface_path.h"

#include <cmath>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

Vec3 position(const Mesh& mesh, const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      return mesh.position(p.element);
    case SurfacePoint::Kind::Edge:
      return (1.0 - p.t) * mesh.position(mesh.from(p.element)) +
             p.t * mesh.position(mesh.to(p.element));
    case SurfacePoint::Kind::Face: {
      const Tri& t = mesh.triangle(p.element);
      return p.bary[0] * mesh.position(t[0]) + p.bary[1] * mesh.position(t[1]) +
             p.bary[2] * mesh.position(t[2]);
    }
  }
  return Vec3::Zero();
}

int containing_face(const Mesh& mesh, const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex: {
      const int h = mesh.vertex_halfedge(p.element);
      return h < 0 ? -1 : mesh.face(h);
    }
    case SurfacePoint::Kind::Edge: {
      const int f = mesh.face(p.element);
      return f >= 0 ? f : mesh.face(mesh.twin(p.element));
    }
    case SurfacePoint::Kind::Face:
      return p.element;
  }
  return -1;
}

bool face_contains(const Mesh& mesh, int f, const SurfacePoint& p) {
  if (f < 0) return false;
  const Tri& t = mesh.triangle(f);
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      return t[0] == p.element || t[1] == p.element || t[2] == p.element;
    case SurfacePoint::Kind::Edge: {
      const int e = mesh.edge(p.element);
      for (int k = 0; k < 3; ++k)
        if (mesh.edge(3 * f + k) == e) return true;
      // An edge point at an endpoint is a vertex point.
      if (p.t <= kOnVertex)
        return face_contains(mesh, f, SurfacePoint::at_vertex(mesh.from(p.element)));
      if (p.t >= 1.0 - kOnVertex)
        return face_contains(mesh, f, SurfacePoint::at_vertex(mesh.to(p.element)));
      return false;
    }
    case SurfacePoint::Kind::Face:
      if (p.element == f) return true;
      // A face point on the face's border may belong to a neighbour too.
      for (int k = 0; k < 3; ++k) {
        if (p.bary[k] >= 1.0 - kOnVertex) {
          return face_contains(mesh, f, SurfacePoint::at_vertex(mesh.triangle(p.element)[k]));
        }
      }
      return false;
  }
  return false;
}

Vec3 barycentric_in_face(const Mesh& mesh, int f, const SurfacePoint& p) {
  const Tri& t = mesh.triangle(f);
  Vec3 b = Vec3::Zero();
  auto add_vertex = [&](int v, double w) {
    for (int k = 0; k < 3; ++k)
      if (t[k] == v) b[k] += w;
  };
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      add_vertex(p.element, 1.0);
      break;
    case SurfacePoint::Kind::Edge:
      add_vertex(mesh.from(p.element), 1.0 - p.t);
      add_vertex(mesh.to(p.element), p.t);
      break;
    case SurfacePoint::Kind::Face:
      if (p.element == f) return p.bary;
      for (int k = 0; k < 3; ++k) add_vertex(mesh.triangle(p.element)[k], p.bary[k]);
      break;
  }
  return b;
}

std::string to_string(const Mesh& mesh, const SurfacePoint& p) {
  std::ostringstream s;
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      s << "vertex " << p.element;
      break;
    case SurfacePoint::Kind::Edge:
      s << "edge " << mesh.from(p.element) << "->" << mesh.to(p.element) << " at t=" << p.t;
      break;
    case SurfacePoint::Kind::Face:
      s << "face " << p.element << " (" << p.bary[0] << "," << p.bary[1] << "," << p.bary[2] << ")";
      break;
  }
  return s.str();
}

int strip_face(const Mesh& mesh, const SurfacePath& path, int i) {
  const int k = path.num_crossings();
  if (k == 0) return path.start_face;
  if (i < k) return mesh.face(path.halfedges[i]);
  return mesh.face(mesh.twin(path.halfedges[k - 1]));
}

std::vector<Vec3> polyline(const Mesh& mesh, const SurfacePath& path) {
  std::vector<Vec3> pts;
  pts.reserve(path.halfedges.size() + 2);
  if (!path.closed) pts.push_back(position(mesh, path.start));
  for (int i = 0; i < path.num_crossings(); ++i) pts.push_back(crossing_position(mesh, path, i));
  if (!path.closed) pts.push_back(position(mesh, path.end));
  return pts;
}

std::vector<int> segment_faces(const Mesh& mesh, const SurfacePath& path) {
  std::vector<int> faces;
  const int k = path.num_crossings();
  if (path.closed) {
    for (int i = 0; i < k; ++i) faces.push_back(mesh.face(mesh.twin(path.halfedges[i])));
  } else {
    for (int i = 0; i <= k; ++i) faces.push_back(strip_face(mesh, path, i));
  }
  return faces;
}

double euclidean_length(const Mesh& mesh, const SurfacePath& path) {
  const std::vector<Vec3> pts = polyline(mesh, path);
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  if (path.closed && pts.size() > 1) len += (pts.front() - pts.back()).norm();
  return len;
}

bool is_valid_path(const Mesh& mesh, const SurfacePath& path, std::string* why) {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  const int k = path.num_crossings();
  if (static_cast<int>(path.lambdas.size()) != k)
    return fail("lambdas and halfedges differ in size");
  for (int i = 0; i < k; ++i) {
    const int h = path.halfedges[i];
    if (h < 0 || h >= mesh.num_interior_halfedges())
      return fail("crossing " + std::to_string(i) + " is not an interior halfedge");
    if (mesh.is_boundary_halfedge(mesh.twin(h)))
      return fail("crossing " + std::to_string(i) + " is on a boundary edge");
    if (!(path.lambdas[i] >= 0.0 && path.lambdas[i] <= 1.0))
      return fail("crossing " + std::to_string(i) + " has lambda outside [0, 1]");
    if (i + 1 < k && mesh.face(mesh.twin(h)) != mesh.face(path.halfedges[i + 1]))
      return fail("crossings " + std::to_string(i) + " and " + std::to_string(i + 1) +
                  " do not share a face");
  }
  if (path.closed) {
    if (k < 2) return fail("a closed loop needs at least two crossings");
    if (mesh.face(mesh.twin(path.halfedges[k - 1])) != mesh.face(path.halfedges[0]))
      return fail("the loop's strip does not close");
  } else {
    if (!face_contains(mesh, strip_face(mesh, path, 0), path.start))
      return fail("the start point is not in the first strip face");
    if (!face_contains(mesh, strip_face(mesh, path, k), path.end))
      return fail("the end point is not in the last strip face");
  }
  return true;
}

}  // namespace windplan
