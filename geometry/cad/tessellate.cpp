#include "geometry/cad/tessellate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <BRepAdaptor_Surface.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_shape_occt.h"
#include "geometry/cad/occt_signals.h"

namespace windplan {

bool TessellateOptions::is_valid(std::string* why) const {
  if (!(linear_deflection > 0.0) || !std::isfinite(linear_deflection)) {
    if (why)
      *why = "linear_deflection must be > 0 mm (got " + std::to_string(linear_deflection) + ")";
    return false;
  }
  if (!(angular_deflection > 0.0) || !(angular_deflection <= 90.0)) {
    if (why) {
      *why = "angular_deflection must be in (0, 90] degrees (got " +
             std::to_string(angular_deflection) + ")";
    }
    return false;
  }
  return true;
}

const char* to_string(CadSurfaceKind kind) {
  switch (kind) {
    case CadSurfaceKind::Plane:
      return "plane";
    case CadSurfaceKind::Cylinder:
      return "cylinder";
    case CadSurfaceKind::Cone:
      return "cone";
    case CadSurfaceKind::Sphere:
      return "sphere";
    case CadSurfaceKind::Torus:
      return "torus";
    case CadSurfaceKind::Revolution:
      return "revolution";
    case CadSurfaceKind::Other:
      return "other";
  }
  return "other";
}

namespace {

Vec3 to_vec(const gp_Pnt& p) { return Vec3(p.X(), p.Y(), p.Z()); }

CadFaceInfo describe_face(const TopoDS_Face& face) {
  CadFaceInfo info;
  BRepAdaptor_Surface surf(face, Standard_False);
  switch (surf.GetType()) {
    case GeomAbs_Plane: {
      info.kind = CadSurfaceKind::Plane;
      gp_Dir n = surf.Plane().Axis().Direction();
      if (face.Orientation() == TopAbs_REVERSED) n.Reverse();
      info.plane_normal = Vec3(n.X(), n.Y(), n.Z());
      break;
    }
    case GeomAbs_Cylinder:
      info.kind = CadSurfaceKind::Cylinder;
      break;
    case GeomAbs_Cone:
      info.kind = CadSurfaceKind::Cone;
      break;
    case GeomAbs_Sphere:
      info.kind = CadSurfaceKind::Sphere;
      break;
    case GeomAbs_Torus:
      info.kind = CadSurfaceKind::Torus;
      break;
    case GeomAbs_SurfaceOfRevolution:
      info.kind = CadSurfaceKind::Revolution;
      break;
    default:
      info.kind = CadSurfaceKind::Other;
      break;
  }
  return info;
}

double signed_volume(const TriangleSoup& s) {
  double v = 0.0;
  for (const Tri& t : s.triangles) {
    v += s.points[t[0]].dot(s.points[t[1]].cross(s.points[t[2]]));
  }
  return v / 6.0;
}

}  // namespace

namespace {

Tessellation tessellate_unguarded(const CadShape& cad, const TessellateOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("tessellation: " + why);
  if (cad.empty() || cad.data()->shape.IsNull()) throw InputError("tessellation: empty CAD shape");
  silence_occt_messages();
  const auto t0 = std::chrono::steady_clock::now();

  // Triangulations live in the (shared) B-rep: drop any earlier one so that these deflections
  // apply, not those of a previous call.
  TopoDS_Shape shape = cad.data()->shape;
  BRepTools::Clean(shape);
  bool done = false;
  {
    OcctSignalScope signals;  // a damaged model's SIGSEGV in BRepMesh becomes a Standard_Failure
    try {
      OCC_CATCH_SIGNALS
      BRepMesh_IncrementalMesh mesher(shape, options.linear_deflection, Standard_False,
                                      options.angular_deflection * M_PI / 180.0, Standard_False);
      done = mesher.IsDone();
    } catch (const Standard_Failure& e) {
      throw InputError(std::string("tessellation: ") +
                       occt_failure_text(e.GetMessageString() ? e.GetMessageString() : ""));
    }
  }
  if (!done) throw InputError("tessellation: BRepMesh failed on the CAD shape");

  TopTools_IndexedMapOfShape face_map, edge_map, vertex_map;
  TopExp::MapShapes(shape, TopAbs_FACE, face_map);
  TopExp::MapShapes(shape, TopAbs_EDGE, edge_map);
  TopExp::MapShapes(shape, TopAbs_VERTEX, vertex_map);
  if (face_map.Extent() == 0) throw InputError("tessellation: the CAD shape has no faces");

  Tessellation out;
  TriangleSoup& soup = out.soup;
  // One mesh vertex per B-rep vertex.
  for (int i = 1; i <= vertex_map.Extent(); ++i) {
    soup.points.push_back(to_vec(BRep_Tool::Pnt(TopoDS::Vertex(vertex_map(i)))));
  }
  // Per B-rep edge: its nodes as mesh vertices, in the edge's parametric order (filled on the
  // first face that uses the edge, reused by the others).
  std::vector<std::vector<int>> edge_nodes(edge_map.Extent() + 1);

  out.faces.resize(face_map.Extent());
  for (int fi = 1; fi <= face_map.Extent(); ++fi) {
    const TopoDS_Face& face = TopoDS::Face(face_map(fi));
    out.faces[fi - 1] = describe_face(face);
    TopLoc_Location loc;
    const Handle(Poly_Triangulation)& tri = BRep_Tool::Triangulation(face, loc);
    if (tri.IsNull()) {
      throw InputError("tessellation: B-rep face " + std::to_string(fi - 1) +
                       " could not be meshed (invalid or degenerate surface)");
    }
    const gp_Trsf trsf = loc.Transformation();
    std::vector<int> local(tri->NbNodes() + 1, -1);  // face node (1-based) -> mesh vertex

    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(ex.Current());
      const int ei = edge_map.FindIndex(edge);
      const Handle(Poly_PolygonOnTriangulation)& poly =
          BRep_Tool::PolygonOnTriangulation(edge, tri, loc);
      if (poly.IsNull()) {
        throw InputError("tessellation: B-rep edge " + std::to_string(ei - 1) + " of face " +
                         std::to_string(fi - 1) + " has no discretisation");
      }
      const TColStd_Array1OfInteger& nodes = poly->Nodes();
      const int n = nodes.Length();
      TopoDS_Vertex vfirst, vlast;
      TopExp::Vertices(TopoDS::Edge(edge.Oriented(TopAbs_FORWARD)), vfirst, vlast);
      const int gfirst = vertex_map.FindIndex(vfirst) - 1;
      const int glast = vertex_map.FindIndex(vlast) - 1;
      if (BRep_Tool::Degenerated(edge)) {
        // A pole: every node of the degenerate edge is the vertex.
        for (int k = nodes.Lower(); k <= nodes.Upper(); ++k) local[nodes(k)] = gfirst;
        continue;
      }
      std::vector<int>& shared = edge_nodes[ei];
      if (shared.empty()) {
        shared.resize(n);
        shared[0] = gfirst;
        shared[n - 1] = glast;
        for (int k = 1; k < n - 1; ++k) {
          shared[k] = static_cast<int>(soup.points.size());
          soup.points.push_back(to_vec(tri->Node(nodes(nodes.Lower() + k)).Transformed(trsf)));
        }
      } else if (static_cast<int>(shared.size()) != n) {
        throw InvariantError("tessellation: B-rep edge " + std::to_string(ei - 1) +
                             " is discretised differently on its two faces (" +
                             std::to_string(shared.size()) + " vs " + std::to_string(n) +
                             " nodes)");
      }
      for (int k = 0; k < n; ++k) local[nodes(nodes.Lower() + k)] = shared[k];
    }
    for (int k = 1; k <= tri->NbNodes(); ++k) {
      if (local[k] >= 0) continue;
      local[k] = static_cast<int>(soup.points.size());
      soup.points.push_back(to_vec(tri->Node(k).Transformed(trsf)));
    }
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (int k = 1; k <= tri->NbTriangles(); ++k) {
      int a, b, c;
      tri->Triangle(k).Get(a, b, c);
      Tri t = {local[a], local[b], local[c]};
      if (reversed) std::swap(t[1], t[2]);
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        ++out.dropped_triangles;
        continue;
      }
      soup.triangles.push_back(t);
      out.triangle_face.push_back(fi - 1);
      ++out.faces[fi - 1].triangles;
    }
  }

  // Outward orientation for closed results: a closed, consistently oriented surface has a
  // positive signed volume iff its normals point outward. (Whether the soup is closed is checked
  // by counting directed edges: in a closed oriented soup every edge has its twin.)
  {
    std::size_t boundary = 0;
    std::vector<std::vector<int>> out_edges(soup.points.size());
    for (const Tri& t : soup.triangles) {
      for (int k = 0; k < 3; ++k) out_edges[t[k]].push_back(t[(k + 1) % 3]);
    }
    for (std::size_t v = 0; v < out_edges.size() && boundary == 0; ++v) {
      for (int w : out_edges[v]) {
        const auto& back = out_edges[w];
        if (std::find(back.begin(), back.end(), static_cast<int>(v)) == back.end()) {
          ++boundary;
          break;
        }
      }
    }
    if (boundary == 0 && !soup.triangles.empty() && signed_volume(soup) < 0.0) {
      for (Tri& t : soup.triangles) std::swap(t[1], t[2]);
      for (CadFaceInfo& f : out.faces) f.plane_normal = -f.plane_normal;
      out.flipped = true;
    }
  }
  out.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace

Tessellation tessellate(const CadShape& cad, const TessellateOptions& options) {
  // The whole tessellation under OCCT's fault handlers: the mesher and the triangulation reads.
  OcctSignalScope signals;
  try {
    OCC_CATCH_SIGNALS
    return tessellate_unguarded(cad, options);
  } catch (const Standard_Failure& e) {
    throw InputError(std::string("tessellation: ") +
                     occt_failure_text(e.GetMessageString() ? e.GetMessageString() : ""));
  }
}

double fitted_angular_deflection(double radius, double band_width) {
  if (!(radius > 0.0) || !(band_width > 0.0)) return 10.0;
  const double deg = std::min(5.0, band_width / 4.0 / radius * 180.0 / M_PI);
  return std::clamp(deg, 1.5, 10.0);
}

}  // namespace windplan
