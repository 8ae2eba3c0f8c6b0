#pragma once
// Internal to the OCCT translation units of geometry/: the content of a CadShape. Never include
// this from a header, nor from a translation unit that includes CGAL (OCCT's Handle macro clashes).
#include <TopoDS_Shape.hxx>

#include "geometry/cad/cad_shape.h"

namespace windplan {

struct CadShapeData {
  TopoDS_Shape shape;
};

inline CadShape make_cad_shape(const TopoDS_Shape& s) {
  auto d = std::make_shared<CadShapeData>();
  d->shape = s;
  return CadShape(std::move(d));
}

}  // namespace windplan
