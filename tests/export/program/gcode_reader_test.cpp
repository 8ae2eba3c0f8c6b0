#include "export/program/gcode_reader.h"

#include <cmath>

#include <gtest/gtest.h>

#include "export/machine/kinematics.h"
#include "export/program/gcode.h"
#include "geometry/base/errors.h"
#include "tests/export/plan_fixtures.h"

namespace windplan {
namespace {

MachineOptions machine(const std::string& kind, const std::string& dialect) {
  MachineOptions m;
  m.kind = kind;
  m.gcode.dialect = dialect;
  m.a.offset = 10;  // not applied to Marlin's A (re-zeroed per circuit)
  m.x.sign = -1;
  m.x.offset = 5;
  return m;
}

TEST(GcodeReader, ReadsBackEveryDialectAndKind) {
  const WindingPlan plan = test::helix_plan(40, 50, 2, 600, 3);
  for (const std::string kind : {"lathe2", "lathe4"}) {
    for (const std::string dialect : {"linuxcnc", "marlin", "fanuc"}) {
      SCOPED_TRACE(kind + " " + dialect);
      const MachineOptions m = machine(kind, dialect);
      const Motion mo = compute_motion(plan, m);
      const GcodeProgram p = read_gcode(gcode_program(mo, "t", m), m, "t");
      ASSERT_EQ(p.blocks.size(), mo.states.size());
      EXPECT_TRUE(p.ended);
      EXPECT_EQ(p.inverse_time, dialect == "linuxcnc");  // feed auto
      for (std::size_t i = 0; i < p.blocks.size(); ++i) {
        const MachineState& s = mo.states[i];
        EXPECT_NEAR(p.blocks[i].a, s.a_deg, 2e-4);
        EXPECT_NEAR(p.blocks[i].x, s.x_mm, 2e-4);
        if (kind == "lathe4") {
          EXPECT_NEAR(p.blocks[i].y, s.y_mm, 2e-4);
          EXPECT_NEAR(p.blocks[i].b, s.b_deg, 2e-4);
        }
        if (i > 0) {
          EXPECT_NEAR(p.blocks[i].feed, s.feed, 1e-4 * s.feed + 1e-4);
        }
      }
    }
  }
}

void expect_error(const std::string& text, const MachineOptions& m, const std::string& what) {
  try {
    read_gcode(text, m, "edit.ngc");
    FAIL() << "no error for: " << what;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(GcodeReader, BadProgramsNameTheLine) {
  const MachineOptions lc = machine("lathe2", "linuxcnc");
  expect_error("G21 G90 G93\nG0 X0 A0\nG1 X1 A1 Q5 F10\nM2\n", lc, "edit.ngc:3: unknown word Q5");
  expect_error("G21 G90 G93\nG0 X0 A0\nG1 X1 Y3 A1 F10\nM2\n", lc, "edit.ngc:3: unknown word Y3");
  expect_error("G21\nG90\nG94\nG0 X0 A0\nG92 A0\nM84\n", lc, "edit.ngc:5: G92 belongs to a marlin");
  expect_error("%\nO1000\nN1 G21 G90 G93\nN2 M98 P1001\nN3 M30\n", lc, "edit.ngc:2: an O program");
  expect_error("G21 G90 G93\nG0 X0 A0\nG2 X1 A1 F10\nM2\n", lc, "edit.ngc:3: unknown code G2");
  expect_error("G21 G90 G93\nG0 X0 A0\nG1 X1 A1\nM2\n", lc, "edit.ngc:3: G1 without a feed");
  expect_error("G21 G90 G93\nG0 X0 A0\nG1 X1 A1 F10\n", lc, "no end code");
  const MachineOptions marlin = machine("lathe2", "marlin");
  expect_error("G21\n(comment)\nG0 X0 A0\nM84\n", marlin, "edit.ngc:2: a '( )' comment");
  expect_error("G21 G93\nG0 X0 A0\nM84\n", marlin, "edit.ngc:1: G93");
  MachineOptions limited = lc;
  limited.x.max = 100;
  expect_error("G21 G90 G93\nG0 X0 A0\nG1 X150 A1 F10\nM2\n", limited,
               "edit.ngc:3: axis X moves to 150, outside its travel");
}

// Issue 28: programs LinuxCNC would refuse were replayed, each now refused with its line.
TEST(GcodeReader, AsStrictAsLinuxCnc) {
  const MachineOptions lc = machine("lathe2", "linuxcnc");
  const std::string head = "G21 G90 G93\nG0 X0 A0\n";
  // X1e10: the code cast overflowed long long (undefined behaviour), the replay passed it.
  expect_error(head + "G1 X10000000000 A1 F10\nM2\n", lc,
               "edit.ngc:3: word X10000000000: the number is out of range");
  expect_error(head + "G1 X1000000 A1 F10\nM2\n", lc,
               "edit.ngc:3: axis X moves to 1000000 mm, beyond 100 m");
  expect_error(head + "G99999999999 X1 A1 F10\nM2\n", lc, "edit.ngc:3: word G99999999999");
  // CR-only line ends: the whole program was one line, one block.
  expect_error("G21 G90 G93\rG0 X0 A0\rG1 X1 A1 F10\rM2\r", lc,
               "edit.ngc:1: a carriage return (CR) inside the line");
  EXPECT_EQ(read_gcode(head + "G1 X1 A1 F10\r\nM2\r\n", lc, "crlf").blocks.size(), 2u);
  // G93: every G1 gives its own F (the modal F was reused).
  expect_error(head + "G1 X1 A1 F10\nG1 X2 A2\nM2\n", lc,
               "edit.ngc:4: G1 without an F word in inverse time mode (G93)");
  EXPECT_EQ(read_gcode("G21 G90 G94\nG0 X0 A0\nG1 X1 A1 F10\nG1 X2 A2\nM2\n", lc).blocks.size(),
            3u);  // G94: F is modal
  expect_error(head + "G1 X1 X2 A1 F10\nM2\n", lc, "edit.ngc:3: two X words on one line");
  expect_error(head + "G1 X1 A1 F10 F20\nM2\n", lc, "edit.ngc:3: two F words on one line");
  expect_error(head + "G0 G1 X1 A1 F10\nM2\n", lc, "edit.ngc:3: two motion codes");
  // A subprogram that calls itself recursed until the step bound (found by fuzz_gcode).
  const MachineOptions fanuc = machine("lathe2", "fanuc");
  expect_error(
      "%\nO1000\nN1 G21 G90 G93\nN2 G0 X0 A0\nN3 M98 P1001\nN4 M30\nO1001\n"
      "N5 G1 X1 A1 F10\nN6 M98 P1001\nN7 M99\n%\n",
      fanuc, "edit.ngc:9: M98 calls O1001 nested more than 10 deep");
  // An M2 after 1 of 3 moves: the rest was silently never replayed.
  expect_error(head + "G1 X1 A1 F10\nM2\nG1 X2 A2 F10\nG1 X3 A3 F10\nM2\n", lc,
               "edit.ngc:4: the end code here stops the program, but 3 more line(s) follow "
               "(from line 5)");
}

// A lathe2 layup (issue #26): the stop before each layer names its eye radius, which the
// operator sets by hand; the moves after it carry it (0 before any stop: the machine's own).
// Written by gcode_program in every dialect with the second layer's eye 6.25 mm further out.
TEST(GcodeReader, Lathe2StopsNameEachLayersEyeRadius) {
  WindingPlan plan = test::two_layer_helix_plan();
  for (const std::string dialect : {"linuxcnc", "marlin", "fanuc"}) {
    SCOPED_TRACE(dialect);
    const MachineOptions m = machine("lathe2", dialect);
    Motion mo = compute_motion(plan, m);
    const double inner = mo.states.front().y_mm, outer = inner + 6.25;
    for (MachineState& s : mo.states) {
      if (s.ordinal >= 2) s.y_mm = outer;
    }
    const std::string text = gcode_program(mo, "t", m);
    const std::string stop = dialect == "fanuc"    ? " M0 (EYE RADIUS " + format_fixed4(outer)
                             : dialect == "marlin" ? "\nM0 ; eye radius " + format_fixed4(outer)
                                                   : "\nM0 (eye radius " + format_fixed4(outer);
    EXPECT_NE(text.find(stop + (dialect == "fanuc" ? " MM" : " mm")), std::string::npos) << stop;
    const GcodeProgram p = read_gcode(text, m, "t");
    ASSERT_EQ(p.blocks.size(), mo.states.size());
    int outer_blocks = 0;
    for (std::size_t i = 0; i < p.blocks.size(); ++i) {
      if (mo.states[i].ordinal < 2) {
        EXPECT_EQ(p.blocks[i].eye_radius, 0.0) << i;
      } else {
        EXPECT_NEAR(p.blocks[i].eye_radius, outer, 5e-5) << i;
        ++outer_blocks;
      }
    }
    EXPECT_GT(outer_blocks, 100);
  }
  // Where an eye radius may be named, and how.
  const MachineOptions lc = machine("lathe2", "linuxcnc");
  const std::string head = "G21 G90 G93\nG0 X0 A0\n";
  const GcodeProgram ok =
      read_gcode(head + "M0 (EYE Radius 71.5 mm: set it)\nG1 X1 A1 F10\nM2\n", lc, "ok");
  ASSERT_EQ(ok.blocks.size(), 2u);
  EXPECT_EQ(ok.blocks[0].eye_radius, 0.0);
  EXPECT_EQ(ok.blocks[1].eye_radius, 71.5);
  expect_error(head + "(eye radius 71.5 mm)\nG1 X1 A1 F10\nM2\n", lc,
               "edit.ngc:3: an eye radius is set by hand at an operator stop");
  expect_error(head + "G1 X1 A1 F10 (eye radius 71.5 mm)\nM2\n", lc,
               "edit.ngc:3: an eye radius is set by hand at an operator stop");
  expect_error(head + "M0 (eye radius -3 mm)\nM2\n", lc,
               "edit.ngc:3: the comment names an eye radius but not as");
  expect_error(head + "M0 (eye radius 71.5 in)\nM2\n", lc,
               "edit.ngc:3: the comment names an eye radius but not as");
  expect_error("G21 G90 G93\nG0 X0 Y70 A0 B0\nM0 (eye radius 71.5 mm)\nM2\n",
               machine("lathe4", "linuxcnc"),
               "edit.ngc:3: an eye radius set by hand: only a lathe2");
}

}  // namespace
}  // namespace windplan
