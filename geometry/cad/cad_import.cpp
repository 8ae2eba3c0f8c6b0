#include "geometry/cad/cad_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_IGESEntity.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include "geometry/base/errors.h"
#include "geometry/base/input_file.h"
#include "geometry/cad/cad_shape_occt.h"
#include "geometry/cad/occt_signals.h"

namespace windplan {

namespace {

std::string lower_ext(const std::filesystem::path& file) {
  std::string e = file.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

std::string format_of(const std::filesystem::path& file) {
  const std::string e = lower_ext(file);
  if (e == ".step" || e == ".stp") return "step";
  if (e == ".iges" || e == ".igs") return "iges";
  if (e == ".brep" || e == ".brp") return "brep";
  return "";
}

std::string head_of(const std::filesystem::path& file, std::size_t n) {
  std::ifstream in(file, std::ios::binary);
  std::string s(n, '\0');
  in.read(&s[0], static_cast<std::streamsize>(n));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

// Cheap signature checks before handing a file to OCCT's parsers, which are noisy and lenient on
// garbage: a STEP file starts with "ISO-10303-21;", an IGES file is made of 80-column records
// whose first one is a Start ('S') or Flag ('G'...) section record, a BREP file starts with
// OCCT's "DBRep_DrawableShape" or "CASCADE Topology" header.
void check_signature(const std::filesystem::path& file, const std::string& format) {
  std::string head = head_of(file, 512);
  const auto first = head.find_first_not_of(" \t\r\n");
  const std::string body = first == std::string::npos ? "" : head.substr(first);
  bool ok = false;
  if (format == "step") {
    ok = body.rfind("ISO-10303-21", 0) == 0;
  } else if (format == "iges") {
    const auto eol = head.find_first_of("\r\n");
    const std::string line = head.substr(0, eol);
    ok = line.size() >= 73 && (line[72] == 'S' || line[72] == 'G' || line[72] == 'F');
  } else {
    ok = body.rfind("DBRep_DrawableShape", 0) == 0 || body.rfind("CASCADE Topology", 0) == 0;
  }
  if (!ok) {
    const char* kind = format == "step"   ? "not a STEP (ISO-10303-21)"
                       : format == "iges" ? "not an IGES"
                                          : "not a BREP";
    throw IoError(file.string() + ": " + kind + " file (its header does not match the extension)");
  }
}

std::string clean_name(const Handle(TCollection_HAsciiString) & n) {
  if (n.IsNull()) return "";
  std::string s = n->ToCString();
  if (s == "NONE" || s == "$") return "";
  return s;
}

struct Body {
  TopoDS_Shape shape;
  std::string name;
  bool solid = false;
  double size = 0.0;  // volume for solids, area for shells
};

int free_edges(const TopoDS_Shape& s) {
  CadShapeInfo info = cad_shape_info(make_cad_shape(s));
  return info.free_edges;
}

}  // namespace

bool CadImportOptions::is_valid(std::string* why) const {
  if (!(brep_unit_to_mm > 0.0) || !std::isfinite(brep_unit_to_mm)) {
    if (why) *why = "the BREP unit scale must be > 0";
    return false;
  }
  if (!(sewing_tolerance > 0.0)) {
    if (why) *why = "sewing_tolerance must be > 0 mm";
    return false;
  }
  return true;
}

bool is_cad_file(const std::filesystem::path& file) { return !format_of(file).empty(); }

namespace {

CadImport import_cad_unguarded(const std::filesystem::path& file, const CadImportOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("CAD import: " + why);
  const std::string name = file.string();
  const std::string format = format_of(file);
  if (format.empty()) {
    throw IoError(name + ": unknown CAD extension '" + file.extension().string() +
                  "' (use .step/.stp, .iges/.igs or .brep)");
  }
  if (check_input_file(file, kCadFileCap, "a STEP, IGES or BREP file") == 0) {
    throw IoError(name + ": the file is empty");
  }
  check_signature(file, format);
  silence_occt_messages();

  CadImport out;
  out.format = format;
  TopoDS_Shape shape;
  // Names of the transferred bodies, looked up from the reader's entities when possible.
  std::vector<std::pair<TopoDS_Shape, std::string>> names;
  OcctSignalScope signals;  // a damaged file's SIGSEGV in OCCT becomes a Standard_Failure
  try {
    OCC_CATCH_SIGNALS
    if (format == "step" || format == "iges") {
      Interface_Static::SetCVal("xstep.cascade.unit", "MM");
      std::unique_ptr<XSControl_Reader> reader;
      if (format == "step") {
        reader = std::make_unique<STEPControl_Reader>();
      } else {
        reader = std::make_unique<IGESControl_Reader>();
      }
      if (reader->ReadFile(name.c_str()) != IFSelect_RetDone) {
        throw IoError(name + ": not a readable " + (format == "step" ? "STEP" : "IGES") +
                      " file (the parser rejected it)");
      }
      reader->TransferRoots();
      if (reader->NbShapes() == 0) {
        throw InputError(name + ": the file contains no shapes (no solids, shells or faces)");
      }
      shape = reader->OneShape();
      Handle(XSControl_TransferReader) tr = reader->WS()->TransferReader();
      for (TopAbs_ShapeEnum kind : {TopAbs_SOLID, TopAbs_SHELL, TopAbs_FACE}) {
        for (TopExp_Explorer ex(shape, kind); ex.More(); ex.Next()) {
          Handle(Standard_Transient) ent =
              tr.IsNull() ? nullptr : tr->EntityFromShapeResult(ex.Current(), 1);
          std::string n;
          if (auto item = Handle(StepRepr_RepresentationItem)::DownCast(ent)) {
            n = clean_name(item->Name());
          } else if (auto ig = Handle(IGESData_IGESEntity)::DownCast(ent)) {
            if (ig->HasName()) n = clean_name(ig->NameValue());
          }
          if (!n.empty()) names.emplace_back(ex.Current(), n);
        }
      }
    } else {
      BRep_Builder builder;
      if (!BRepTools::Read(shape, name.c_str(), builder) || shape.IsNull()) {
        throw IoError(name + ": not a readable BREP file");
      }
      if (options.brep_unit_to_mm != 1.0) {
        gp_Trsf scale;
        scale.SetScale(gp::Origin(), options.brep_unit_to_mm);
        shape = BRepBuilderAPI_Transform(shape, scale, Standard_True).Shape();
      }
    }
  } catch (const Standard_Failure& e) {
    const std::string what = e.GetMessageString() ? e.GetMessageString() : "";
    if (what.find("SIG") != std::string::npos) throw IoError(name + ": " + occt_failure_text(what));
    throw IoError(name + ": OpenCASCADE could not read it (" + what + ")");
  }
  if (shape.IsNull()) throw InputError(name + ": the file contains no shapes");

  auto name_of = [&](const TopoDS_Shape& s, const std::string& fallback) {
    for (const auto& [sh, n] : names) {
      if (sh.IsSame(s)) return n;
    }
    return fallback;
  };

  std::vector<Body> bodies;
  try {
    OCC_CATCH_SIGNALS
    for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) {
      Body b;
      b.shape = ex.Current();
      b.solid = true;
      b.name = name_of(b.shape, "solid " + std::to_string(bodies.size() + 1));
      b.size = cad_shape_info(make_cad_shape(b.shape)).volume;
      bodies.push_back(b);
    }
    if (bodies.empty()) {
      TopTools_IndexedMapOfShape faces;
      TopExp::MapShapes(shape, TopAbs_FACE, faces);
      if (faces.Extent() == 0) {
        TopTools_IndexedMapOfShape edges, vertices;
        TopExp::MapShapes(shape, TopAbs_EDGE, edges);
        TopExp::MapShapes(shape, TopAbs_VERTEX, vertices);
        throw InputError(name + ": the file has no surfaces, only " +
                         std::to_string(edges.Extent()) + " curve(s) and " +
                         std::to_string(vertices.Extent()) +
                         " point(s); a mandrel needs a solid or a shell");
      }
      // Loose faces (typical of IGES) or open shells: sew them into shells.
      BRepBuilderAPI_Sewing sew(options.sewing_tolerance);
      for (int i = 1; i <= faces.Extent(); ++i) sew.Add(faces(i));
      sew.Perform();
      const TopoDS_Shape sewn = sew.SewedShape();
      out.sewn = faces.Extent() > 1;
      std::vector<TopoDS_Shape> shells;
      for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next())
        shells.push_back(ex.Current());
      for (TopExp_Explorer ex(sewn, TopAbs_FACE, TopAbs_SHELL); ex.More(); ex.Next()) {
        TopoDS_Shell sh;
        BRep_Builder bb;
        bb.MakeShell(sh);
        bb.Add(sh, ex.Current());
        shells.push_back(sh);
      }
      for (const TopoDS_Shape& sh : shells) {
        Body b;
        const std::string fallback = "shell " + std::to_string(bodies.size() + 1);
        if (free_edges(sh) == 0) {
          BRepBuilderAPI_MakeSolid mk(TopoDS::Shell(sh));
          if (mk.IsDone()) {
            TopoDS_Solid solid = mk.Solid();
            BRepLib::OrientClosedSolid(solid);
            b.shape = solid;
            b.solid = true;
            b.size = cad_shape_info(make_cad_shape(solid)).volume;
          }
        }
        if (!b.solid) {
          b.shape = sh;
          b.size = cad_shape_info(make_cad_shape(sh)).area;
        }
        b.name = name_of(sh, fallback);
        bodies.push_back(b);
      }
      // Prefer solids: drop shells when sewing closed some of them.
      if (std::any_of(bodies.begin(), bodies.end(), [](const Body& b) { return b.solid; })) {
        bodies.erase(
            std::remove_if(bodies.begin(), bodies.end(), [](const Body& b) { return !b.solid; }),
            bodies.end());
      }
    }
  } catch (const Standard_Failure& e) {
    const std::string what = e.GetMessageString() ? e.GetMessageString() : "";
    if (what.find("SIG") != std::string::npos) throw IoError(name + ": " + occt_failure_text(what));
    throw IoError(name + ": OpenCASCADE failed on its topology (" + what + ")");
  }
  if (bodies.empty()) throw InputError(name + ": the file has no usable solid or shell");
  for (const Body& b : bodies) out.bodies.push_back(b.name);

  std::size_t pick = 0;
  if (!options.solid.empty()) {
    bool found = false;
    for (std::size_t i = 0; i < bodies.size() && !found; ++i) {
      if (bodies[i].name == options.solid) {
        pick = i;
        found = true;
      }
    }
    if (!found) {
      char* end = nullptr;
      const long idx = std::strtol(options.solid.c_str(), &end, 10);
      if (end && *end == '\0' && idx >= 1 && idx <= static_cast<long>(bodies.size())) {
        pick = static_cast<std::size_t>(idx - 1);
        found = true;
      }
    }
    if (!found) {
      std::string list;
      for (const Body& b : bodies) list += (list.empty() ? "'" : ", '") + b.name + "'";
      throw InputError(name + ": no body '" + options.solid + "' (mandrel.solid); the file has " +
                       std::to_string(bodies.size()) + ": " + list +
                       " (a name or a 1-based index)");
    }
  } else if (bodies.size() > 1) {
    for (std::size_t i = 1; i < bodies.size(); ++i) {
      if (bodies[i].size > bodies[pick].size) pick = i;
    }
    std::string others;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (i != pick) others += (others.empty() ? "'" : ", '") + bodies[i].name + "'";
    }
    std::ostringstream w;
    w << name << " has " << bodies.size() << " bodies; took the largest, '" << bodies[pick].name
      << "' (" << (bodies[pick].solid ? "volume " : "area ") << bodies[pick].size
      << (bodies[pick].solid ? " mm^3" : " mm^2") << "), ignored " << others
      << " (set mandrel.solid to choose)";
    out.warnings.push_back(w.str());
  }
  const Body& chosen = bodies[pick];
  out.shape = make_cad_shape(chosen.shape);
  out.selected = chosen.name;
  out.is_solid = chosen.solid;
  const int free = free_edges(chosen.shape);
  out.closed = free == 0;
  if (!out.closed) {
    const std::string msg = name + ": the selected body '" + chosen.name + "' is an open shell (" +
                            std::to_string(free) + " free edges), not a closed solid";
    if (options.require_closed) throw InputError(msg);
    out.warnings.push_back(msg);
  }
  return out;
}

}  // namespace

CadImport import_cad(const std::filesystem::path& file, const CadImportOptions& options) {
  // The whole import under OCCT's fault handlers, not only the reader and the sewing: a fault in
  // the topology queries after them (free edges, volumes) is reported with the file too.
  OcctSignalScope signals;
  try {
    OCC_CATCH_SIGNALS
    return import_cad_unguarded(file, options);
  } catch (const Standard_Failure& e) {
    throw IoError(file.string() + ": " +
                  occt_failure_text(e.GetMessageString() ? e.GetMessageString() : ""));
  }
}

}  // namespace windplan
