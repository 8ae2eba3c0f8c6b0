#include "geometry/cad/cad_export.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <unistd.h>
#include <BRepTools.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/cad/cad_shape_occt.h"

namespace windplan {

void export_cad(const CadShape& cad, const std::filesystem::path& file,
                const CadExportOptions& options) {
  if (cad.empty() || cad.data()->shape.IsNull()) {
    throw IoError(file.string() + ": nothing to write (empty CAD shape)");
  }
  std::string e = file.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  silence_occt_messages();
  const TopoDS_Shape& shape = cad.data()->shape;
  try {
    if (e == ".step" || e == ".stp") {
      // STEPControl_Writer only writes to a named file: write a private temporary file, then
      // copy its bytes into place atomically.
      const std::filesystem::path tmp =
          std::filesystem::temp_directory_path() /
          ("windplan-" + std::to_string(::getpid()) + "-" + file.filename().string());
      Interface_Static::SetCVal("write.step.unit", "MM");
      Interface_Static::SetCVal("write.step.product.name", file.stem().string().c_str());
      STEPControl_Writer writer;
      if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone ||
          writer.Write(tmp.string().c_str()) != IFSelect_RetDone) {
        std::filesystem::remove(tmp);
        throw IoError(file.string() + ": OpenCASCADE could not write the STEP file");
      }
      std::string bytes;
      try {
        bytes = read_text_file(tmp);
      } catch (...) {
        std::filesystem::remove(tmp);
        throw;
      }
      std::filesystem::remove(tmp);
      write_text_atomically(file, bytes);
    } else if (e == ".iges" || e == ".igs") {
      IGESControl_Controller::Init();
      // Mode 1: B-rep solids (MSBO entities); mode 0: loose trimmed surfaces.
      IGESControl_Writer writer("MM", options.iges_loose_faces ? 0 : 1);
      writer.AddShape(shape);
      writer.ComputeModel();
      write_file_atomically(file, [&](std::ostream& os) {
        if (!writer.Write(os)) throw IoError(file.string() + ": could not write the IGES file");
      });
    } else if (e == ".brep" || e == ".brp") {
      write_file_atomically(file, [&](std::ostream& os) { BRepTools::Write(shape, os); });
    } else {
      throw IoError(file.string() + ": unknown CAD extension '" + file.extension().string() +
                    "' (use .step, .iges or .brep)");
    }
  } catch (const Standard_Failure& ex) {
    throw IoError(file.string() + ": OpenCASCADE failed writing it (" + ex.GetMessageString() +
                  ")");
  }
}

}  // namespace windplan
