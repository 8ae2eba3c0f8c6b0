#include "export/program/gcode.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/export/gcode_parser.h"
#include "tests/export/plan_fixtures.h"
#include "windplan_version.h"

namespace windplan {
namespace {

MachineOptions machine(const std::string& kind, const std::string& dialect) {
  MachineOptions m;
  m.kind = kind;
  m.gcode.dialect = dialect;
  m.chord_tolerance = 0.02;
  // Non-trivial letters, signs and offsets: the readback must undo them.
  m.a.letter = "C";
  m.a.sign = -1;
  m.a.offset = 12.5;
  m.x.letter = "Z";
  m.x.offset = -100;
  m.y.sign = -1;
  m.b.letter = "A";
  m.b.offset = 3;
  return m;
}

// Reads the program back and compares every move with the motion it came from.
void check_readback(const std::string& kind, const std::string& dialect) {
  SCOPED_TRACE(kind + " " + dialect);
  const WindingPlan plan = test::helix_plan(45, 40, 1.5, 600, 4);
  const MachineOptions m = machine(kind, dialect);
  const Motion mo = compute_motion(plan, m);
  const std::string text = gcode_program(mo, plan.job_name, m);
  const test::ParsedGcode g = test::parse_gcode(text);
  EXPECT_TRUE(g.ended);
  ASSERT_EQ(g.moves.size(), mo.states.size());
  const bool marlin = dialect == "marlin";
  const double q = 0.5e-4 + 1e-9;  // output precision
  for (std::size_t i = 0; i < mo.states.size(); ++i) {
    const MachineState& s = mo.states[i];
    const test::GcodeMove& mv = g.moves[i];
    EXPECT_EQ(mv.rapid, i == 0);
    const double a = marlin ? -mv.pos.at('C') : -(mv.pos.at('C') - 12.5);
    EXPECT_NEAR(a, s.a_deg, q) << i;
    EXPECT_NEAR(mv.pos.at('Z') + 100, s.x_mm, q) << i;
    if (kind == "lathe4") {
      EXPECT_NEAR(-mv.pos.at('Y'), s.y_mm, q) << i;
      EXPECT_NEAR(mv.pos.at('A') - 3, s.b_deg, q) << i;
    } else {
      EXPECT_EQ(mv.pos.count('Y'), 0u);
      EXPECT_EQ(mv.pos.count('A'), 0u);
    }
    if (i > 0) {
      EXPECT_NEAR(mv.feed, s.feed, q) << i;
    }
  }
  // Velocity limits hold on what the machine reads (inverse time: duration = 60 / F seconds).
  if (mo.inverse_time) {
    for (std::size_t i = 1; i < g.moves.size(); ++i) {
      const double dur = 60.0 / g.moves[i].feed;
      for (const auto& [letter, vmax] :
           std::map<char, double>{{'C', m.a.max_velocity}, {'Z', m.x.max_velocity}}) {
        const double d = std::fabs(g.moves[i].pos.at(letter) - g.moves[i - 1].pos.at(letter));
        EXPECT_LE(d / dur, vmax * (1 + 1e-6) + 2e-4 / dur) << i;
      }
    }
  }
  // Dialect framing.
  EXPECT_NE(text.find(dialect == "fanuc" ? "WINDPLAN" : "windplan"), std::string::npos);
  EXPECT_NE(text.find(WINDPLAN_VERSION), std::string::npos);
  if (dialect == "linuxcnc") {
    EXPECT_EQ(text.rfind("%\n", 0), 0u);
    EXPECT_NE(text.find("G21 G90 G93"), std::string::npos);
    EXPECT_NE(text.find("\nM2\n%\n"), std::string::npos);
  } else if (marlin) {
    int g92 = 0;
    for (const std::string& c : g.codes) g92 += c == "G92";
    EXPECT_EQ(g92, 4);  // one per circuit
    EXPECT_NE(text.find("\nM84\n"), std::string::npos);
    // The re-zeroed spindle stays within one circuit's turns.
    for (const std::string& line : {std::string("C-1000"), std::string("C1000")}) {
      EXPECT_EQ(text.find(line), std::string::npos);
    }
  } else {
    EXPECT_NE(text.find("O1000"), std::string::npos);
    EXPECT_EQ(g.subprogram_calls, 4);
    EXPECT_NE(text.find("M98 P1004"), std::string::npos);
    EXPECT_NE(text.find("O1004"), std::string::npos);
    EXPECT_NE(text.find(" M30\n"), std::string::npos);
    EXPECT_NE(text.find("N1 G21 G90 G94"), std::string::npos);
    int m99 = 0;
    for (const std::string& c : g.codes) m99 += c == "M99";
    EXPECT_EQ(m99, 4);
  }
}

// A layup whose second layer starts with a circuit of no points (compute_motion skips it: no
// states): the layer's stop, its eye radius (lathe2) and the rapid that ties the tow on go
// before its first circuit with points, as without the empty circuit (they were left out).
TEST(Gcode, ALayerStartingWithAnEmptyCircuitKeepsItsStop) {
  WindingPlan plan = test::two_layer_helix_plan();
  WindingPlan with_empty = plan;
  with_empty.circuits.insert(with_empty.circuits.begin() + 2, Circuit{});
  with_empty.layers[1].circuit_count = 3;
  for (const std::string dialect : {"linuxcnc", "marlin", "fanuc"}) {
    SCOPED_TRACE(dialect);
    const MachineOptions m = machine("lathe2", dialect);
    const std::string a = gcode_program(compute_motion(plan, m), "t", m);
    const std::string b = gcode_program(compute_motion(with_empty, m), "t", m);
    const std::string stop = dialect == "fanuc" ? "M0 (EYE RADIUS " : "eye radius ";
    ASSERT_NE(a.find(stop), std::string::npos);
    EXPECT_NE(b.find(stop), std::string::npos) << b.substr(0, 2000);
    // The same program but the layer comment's circuit range ("circuits 2 to 3" / "2 to 4").
    std::string b_as_a = b;
    const std::string range = dialect == "fanuc" ? "CIRCUITS 2 TO 4" : "circuits 2 to 4";
    if (const auto at = b_as_a.find(range); at != std::string::npos) {
      b_as_a.replace(at, range.size(), dialect == "fanuc" ? "CIRCUITS 2 TO 3" : "circuits 2 to 3");
    }
    EXPECT_EQ(b_as_a, a);
  }
}

TEST(Gcode, LinuxcncReadbackReproducesAxes) {
  check_readback("lathe2", "linuxcnc");
  check_readback("lathe4", "linuxcnc");
}
TEST(Gcode, MarlinReadbackFollowsG92) {
  check_readback("lathe2", "marlin");
  check_readback("lathe4", "marlin");
}
TEST(Gcode, FanucReadbackFollowsSubprograms) {
  check_readback("lathe2", "fanuc");
  check_readback("lathe4", "fanuc");
}

TEST(Gcode, ExtensionsAndRobot) {
  EXPECT_EQ(gcode_extension("linuxcnc"), ".ngc");
  EXPECT_EQ(gcode_extension("marlin"), ".gcode");
  EXPECT_EQ(gcode_extension("fanuc"), ".nc");
  MachineOptions m;
  m.kind = "robot";
  EXPECT_THROW(gcode_program(Motion{}, "x", m), InputError);
  EXPECT_EQ(format_fixed4(-0.00001), "0.0000");
  EXPECT_EQ(format_fixed4(-1.23456), "-1.2346");
  EXPECT_EQ(format_fixed4(7), "7.0000");
}

TEST(Gcode, FanucProgramNumbersAreBounded) {
  const WindingPlan plan = test::helix_plan(45, 40, 0.2, 3, 1100);
  MachineOptions m;
  m.gcode.dialect = "fanuc";
  m.gcode.program_number = 8950;
  const Motion mo = compute_motion(plan, m);
  EXPECT_THROW(gcode_program(mo, "x", m), InputError);
}

}  // namespace
}  // namespace windplan
