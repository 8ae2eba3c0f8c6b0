#pragma once
// An opaque handle on an OpenCASCADE B-rep shape (a solid, a shell or a compound), so that code
// passing CAD shapes around (planner, CLI, tests) never includes OCCT headers. Only the OCCT
// translation units of geometry/ (cad_import, tessellate, parametric_mandrel, cad_export) look
// inside, through geometry/cad/cad_shape_occt.h.
#include <memory>
#include <string>

namespace windplan {

struct CadShapeData;  // holds the TopoDS_Shape; defined in geometry/cad/cad_shape_occt.h

/// A B-rep shape in millimetres. Copies share the same (immutable) shape.
class CadShape {
 public:
  CadShape() = default;
  explicit CadShape(std::shared_ptr<const CadShapeData> data) : data_(std::move(data)) {}
  bool empty() const { return data_ == nullptr; }
  const CadShapeData* data() const { return data_.get(); }

 private:
  std::shared_ptr<const CadShapeData> data_;
};

/// Summary figures of a shape: counts of B-rep entities, area (mm^2) and volume (mm^3, 0 for a
/// shell) from OCCT's exact global properties.
struct CadShapeInfo {
  int solids = 0;
  int shells = 0;
  int faces = 0;
  int edges = 0;
  int vertices = 0;
  int free_edges = 0;  ///< edges bounding only one face (0 for a closed shell or solid)
  double area = 0.0;
  double volume = 0.0;
};

/// Counts and exact area/volume of `shape`. \throw InvariantError for an empty shape.
CadShapeInfo cad_shape_info(const CadShape& shape);

/// Turns off OCCT's console messages (reader banners and statistics go to stdout otherwise, which
/// would break `--json` output). Idempotent; every OCCT entry point of windplan calls it.
void silence_occt_messages();

}  // namespace windplan
