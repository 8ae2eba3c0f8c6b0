#include "geometry/cad/cad_shape.h"

#include <mutex>

#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <TopAbs.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_shape_occt.h"

namespace windplan {

void silence_occt_messages() {
  static std::once_flag once;
  std::call_once(once, [] {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    // Drop every printer: OCCT readers write banners and statistics through them.
    m->ChangePrinters().Clear();
  });
}

CadShapeInfo cad_shape_info(const CadShape& cad) {
  if (cad.empty() || cad.data()->shape.IsNull())
    throw InvariantError("cad_shape_info: empty shape");
  const TopoDS_Shape& s = cad.data()->shape;
  CadShapeInfo info;
  TopTools_IndexedMapOfShape m;
  TopExp::MapShapes(s, TopAbs_SOLID, m);
  info.solids = m.Extent();
  m.Clear();
  TopExp::MapShapes(s, TopAbs_SHELL, m);
  info.shells = m.Extent();
  m.Clear();
  TopExp::MapShapes(s, TopAbs_FACE, m);
  info.faces = m.Extent();
  m.Clear();
  TopExp::MapShapes(s, TopAbs_VERTEX, m);
  info.vertices = m.Extent();
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(s, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  info.edges = edge_faces.Extent();
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edge_faces.FindKey(i));
    if (BRep_Tool::Degenerated(e)) continue;
    // A seam edge appears twice in the list of its only face: it is not free.
    const TopTools_ListOfShape& faces = edge_faces.FindFromIndex(i);
    if (faces.Extent() == 1 && !BRep_Tool::IsClosed(e, TopoDS::Face(faces.First()))) {
      ++info.free_edges;
    }
  }
  GProp_GProps area;
  BRepGProp::SurfaceProperties(s, area);
  info.area = area.Mass();
  if (info.solids > 0) {
    GProp_GProps vol;
    BRepGProp::VolumeProperties(s, vol);
    info.volume = vol.Mass();
  }
  return info;
}

}  // namespace windplan
