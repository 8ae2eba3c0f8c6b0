// CAD import: STEP/IGES/BREP round trips (same area and topology), loose IGES faces sewn, body
// selection, and every kind of bad file refused with the file named.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_export.h"
#include "geometry/cad/cad_import.h"
#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_validation.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() /
                     ("windplan_cad_import_test_" +
                      std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(d);
  return d;
}

fs::path data(const std::string& name) { return test::source_dir() / "tests/data/cad" / name; }

struct Meshed {
  double area;
  MeshHealth health;
};

Meshed mesh_of(const CadShape& s) {
  const Tessellation t = tessellate(s);
  return {Mesh(t.soup).total_area(), check_mesh(t.soup)};
}

void expect_same_closed_body(const CadShape& original, const CadImport& back) {
  EXPECT_TRUE(back.is_solid);
  EXPECT_TRUE(back.closed);
  const CadShapeInfo a = cad_shape_info(original), b = cad_shape_info(back.shape);
  EXPECT_NEAR(b.area, a.area, 1e-5 * a.area);
  EXPECT_NEAR(b.volume, a.volume, 1e-5 * a.volume);
  EXPECT_EQ(b.free_edges, 0);
  const Meshed m0 = mesh_of(original), m1 = mesh_of(back.shape);
  // Both tessellations are within the deflection (0.25 mm) of the same surfaces: their areas
  // agree to 2 delta / r_min (r_min = 30 mm polar opening).
  EXPECT_NEAR(m1.area, m0.area, 2 * 0.25 / 30 * m0.area);
  EXPECT_TRUE(m1.health.closed);
  EXPECT_TRUE(m1.health.manifold);
  EXPECT_TRUE(m1.health.oriented);
  EXPECT_EQ(m1.health.genus, 0);
  EXPECT_EQ(m1.health.num_components, 1);
}

TEST(CadImport, StepRoundTrip) {
  VesselParams v;
  v.dome_start.type = v.dome_end.type = DomeType::Isotensoid;
  const CadShape s = make_vessel(v);
  const fs::path f = temp_dir() / "vessel.step";
  export_cad(s, f);
  const CadImport back = import_cad(f);
  EXPECT_EQ(back.format, "step");
  EXPECT_TRUE(back.warnings.empty());
  expect_same_closed_body(s, back);
}

TEST(CadImport, IgesRoundTripAsSolid) {
  const CadShape s = make_vessel({});
  const fs::path f = temp_dir() / "vessel.iges";
  export_cad(s, f);
  const CadImport back = import_cad(f);
  EXPECT_EQ(back.format, "iges");
  expect_same_closed_body(s, back);
}

TEST(CadImport, IgesLooseFacesAreSewn) {
  const CadShape s = make_vessel({});
  const fs::path f = temp_dir() / "vessel_faces.igs";
  CadExportOptions o;
  o.iges_loose_faces = true;
  export_cad(s, f, o);
  const CadImport back = import_cad(f);
  EXPECT_TRUE(back.sewn);
  expect_same_closed_body(s, back);
}

TEST(CadImport, BrepRoundTripAndUnitScale) {
  const CadShape s = make_pipe({50, 500});
  const fs::path f = temp_dir() / "pipe.brep";
  export_cad(s, f);
  expect_same_closed_body(s, import_cad(f));
  CadImportOptions o;
  o.brep_unit_to_mm = 10.0;  // the file in cm
  const CadImport cm = import_cad(f, o);
  EXPECT_NEAR(cad_shape_info(cm.shape).area, 100.0 * cad_shape_info(s).area,
              1e-6 * 100.0 * cad_shape_info(s).area);
}

TEST(CadImport, SeveralSolidsTakeTheLargestWithAWarning) {
  const CadImport imp = import_cad(data("two_solids.step"));
  ASSERT_EQ(imp.bodies.size(), 2u);
  ASSERT_EQ(imp.warnings.size(), 1u);
  EXPECT_NE(imp.warnings[0].find("largest"), std::string::npos);
  EXPECT_NE(imp.warnings[0].find(imp.bodies[0] == imp.selected ? imp.bodies[1] : imp.bodies[0]),
            std::string::npos)
      << "the warning names the ignored body: " << imp.warnings[0];
  // The cylinder (R 20, H 100) has 20x the volume of the 10x20x30 box.
  EXPECT_NEAR(cad_shape_info(imp.shape).volume, M_PI * 400 * 100, 1e-6 * M_PI * 4e4);
  // Choosing by index takes the other one, without a warning.
  for (const char* idx : {"1", "2"}) {
    CadImportOptions o;
    o.solid = idx;
    const CadImport one = import_cad(data("two_solids.step"), o);
    EXPECT_TRUE(one.warnings.empty());
    EXPECT_EQ(one.selected, one.bodies[std::stoi(idx) - 1]);
  }
  CadImportOptions bad;
  bad.solid = "flange";
  try {
    import_cad(data("two_solids.step"), bad);
    ADD_FAILURE() << "no error for an unknown body";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flange"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("two_solids.step"), std::string::npos) << e.what();
  }
}

void expect_error_naming_file(const fs::path& f, const std::string& needle,
                              const CadImportOptions& o = {}) {
  try {
    import_cad(f, o);
    ADD_FAILURE() << "no error for " << f;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(f.filename().string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(needle), std::string::npos) << msg;
  }
}

TEST(CadImport, BadFilesAreRefusedNamingTheFile) {
  const fs::path d = temp_dir();
  {
    std::ofstream(d / "notes.step") << "this is a text file, not a model\n";
    std::ofstream(d / "empty.step");
    std::ofstream(d / "broken.step") << "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('x'),'2;1');\n";
    std::ofstream(d / "notes.igs") << "hello\n";
    std::ofstream(d / "notes.brep") << "hello\n";
  }
  expect_error_naming_file(d / "notes.step", "not a STEP");
  expect_error_naming_file(d / "empty.step", "empty");
  expect_error_naming_file(d / "broken.step", "STEP");
  expect_error_naming_file(d / "missing.step", "no such file");
  expect_error_naming_file(d / "notes.igs", "not an IGES");
  expect_error_naming_file(d / "notes.brep", "not a BREP");
  expect_error_naming_file(d / "model.dwg", "unknown CAD extension");
  EXPECT_THROW(import_cad(d / "notes.step"), IoError);
}

TEST(CadImport, WiresOnlyIsRefused) {
  expect_error_naming_file(data("wire_only.step"), "no surfaces");
}

TEST(CadImport, OpenShellIsReportedOrRefused) {
  const CadImport imp = import_cad(data("single_face.step"));
  EXPECT_FALSE(imp.is_solid);
  EXPECT_FALSE(imp.closed);
  ASSERT_EQ(imp.warnings.size(), 1u);
  EXPECT_NE(imp.warnings[0].find("open shell (4 free edges)"), std::string::npos)
      << imp.warnings[0];
  const Tessellation t = tessellate(imp.shape);
  EXPECT_NEAR(Mesh(t.soup).total_area(), 50.0 * 30.0, 1e-9 * 1500.0);
  EXPECT_FALSE(check_mesh(t.soup).closed);
  CadImportOptions o;
  o.require_closed = true;
  expect_error_naming_file(data("single_face.step"), "open shell", o);
}

// Issue 28: a truncated IGES file crashed the process with SIGSEGV inside OpenCASCADE's reader
// (8 of 9 truncation points). tests/data/cad/cylinder.igs is a cylinder r 50, h 200 written by
// OCCT's IGES writer; every truncation is now read or refused with the file named, never a crash
// (before the fix this test died with SIGSEGV at 70 % and 90 %).
TEST(CadImport, TruncatedIgesIsRefusedNeverACrash) {
  const fs::path dir = temp_dir();
  std::ifstream in(data("cylinder.igs"), std::ios::binary);
  const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(whole.size(), 7000u);
  int refused = 0;
  for (int percent = 5; percent < 100; percent += 5) {
    const fs::path cut = dir / ("cut" + std::to_string(percent) + ".igs");
    std::ofstream(cut, std::ios::binary) << whole.substr(0, whole.size() * percent / 100);
    try {
      const CadImport c = import_cad(cut);
      (void)tessellate(c.shape);
    } catch (const InputError& e) {
      ++refused;
      EXPECT_NE(std::string(e.what()).find(cut.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(refused, 10);
  // The whole file still reads: a closed cylinder.
  const CadImport c = import_cad(data("cylinder.igs"));
  EXPECT_NEAR(cad_shape_info(c.shape).area, 2 * M_PI * 50 * (200 + 50), 1e-3);
  fs::remove_all(dir);
}

// Issue 28, found by fuzz_cad: an entity that is its own part (a TRIMMED_CURVE whose basis curve
// is itself; an ORIENTED_EDGE whose edge is itself) sends OpenCASCADE's STEP translator into
// endless recursion; the stack overflowed and the process died with SIGSEGV and no message (OCCT's
// fault handler ran on the overflowed stack). The handler now runs on an alternate stack, so the
// overflow is an exception like any other fault: OCCT's translator drops the entity, and the file
// is read without it or refused with the file named. Before the fix both cases died.
TEST(CadImport, AnEntityThatIsItsOwnPartIsRefusedNeverACrash) {
  const fs::path dir = temp_dir();
  auto with_cycle = [&](const std::string& source, const std::string& from, const std::string& to) {
    std::ifstream in(data(source), std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    const fs::path cyclic = dir / ("cyclic_" + source);
    std::ofstream(cyclic, std::ios::binary) << text;
    return cyclic;
  };
  // wire_only.step with #30's basis curve #31 -> #30: the curve is dropped (2 of 3 are left), and
  // the file is refused for what it lacks, not killed.
  const fs::path curve =
      with_cycle("wire_only.step", "#30 = TRIMMED_CURVE('',#31,", "#30 = TRIMMED_CURVE('',#30,");
  expect_error_naming_file(curve, "only 2 curve(s)");
  // single_face.step with #20's edge #21 -> #20: the face's loop is lost with it.
  const fs::path edge = with_cycle("single_face.step", "#20 = ORIENTED_EDGE('',*,*,#21,",
                                   "#20 = ORIENTED_EDGE('',*,*,#20,");
  try {
    const CadImport c = import_cad(edge);
    (void)tessellate(c.shape);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(edge.string()), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace windplan
