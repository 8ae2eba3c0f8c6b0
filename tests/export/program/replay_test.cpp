#include "export/program/replay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "export/program/gcode_reader.h"
#include "geometry/base/errors.h"
#include "tests/export/plan_fixtures.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

// A lathe2 program written by hand from the closed form: the eye on the cylinder R_e about z
// leads the helix point (R cos phi, R sin phi, c phi) by the angle beta = acos(R / R_e) and by
// c tan(beta) along the axis (the tangent line of the helix leaves the eye cylinder there).
std::string helix_program(double R, double Re, double c, double turns, int n, double fault_mm = 0,
                          int fault_from = -1) {
  const double beta = std::acos(R / Re);
  std::string s = "%\n(hand-made helix)\nG21 G90 G93\n";
  for (int i = 0; i < n; ++i) {
    const double phi = turns * 2 * M_PI * i / (n - 1);
    double x = c * phi + c * std::tan(beta);
    if (fault_from >= 0 && i >= fault_from) x += fault_mm;
    const double a = -(phi + beta) * 180 / M_PI;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s X%.4f A%.4f%s\n", i == 0 ? "G0" : "G1", x, a,
                  i == 0 ? "" : " F600");
    s += buf;
  }
  return s + "M2\n%\n";
}

// 1500 blocks of one layer's helix (its pitch c per radian, n_turns turns from the angle psi and
// the axial z0; c < 0 runs down), its eye on the cylinder Re by the closed form of helix_program,
// the first block a G0 (the tow tied on). `slack`: the eye starts with that fraction of its lead
// missing (the free fibre lifts off the first point: the contact stays on it), taken up over the
// first 100 blocks.
std::string helix_blocks(double r, double Re, double c, double n_turns, double psi, double z0,
                         double slack = 0.0) {
  std::string s;
  for (int i = 0; i < 1500; ++i) {
    const double beta = std::acos(r / Re) * (1.0 - slack * std::max(0.0, 1.0 - i / 100.0));
    const double phi = n_turns * 2 * M_PI * i / 1499;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s X%.4f A%.4f%s\n", i == 0 ? "G0" : "G1",
                  z0 + c * phi + c * std::tan(beta), -(phi + psi + beta) * 180 / M_PI,
                  i == 0 ? "" : " F600");
    s += buf;
  }
  return s;
}

MachineOptions lathe2(double Re) {
  MachineOptions m;
  m.kind = "lathe2";
  m.envelope.radius = Re;
  return m;
}

TEST(Replay, HandMadeHelixProgramOnACylinderLaysTheHelix) {
  const double R = 50, Re = 70, alpha = 60, turns = 2;
  const WindingPlan plan = test::helix_plan(R, alpha, turns, 2000);
  const double c = R / std::tan(alpha * M_PI / 180);
  const Mesh mesh(test::open_cylinder(R, c * turns * 2 * M_PI + 100, 512, 200));
  const MachineOptions m = lathe2(Re);
  const GcodeProgram p = read_gcode(helix_program(R, Re, c, turns, 1500), m, "helix.ngc");
  ASSERT_EQ(p.blocks.size(), 1500u);
  const ReplayResult r = replay_program(p, plan, mesh, m);
  std::printf("%s\n", r.summary.c_str());
  EXPECT_LT(r.max_deviation, 0.05);
  EXPECT_NEAR(r.min_clearance, Re - R, 0.01);
  EXPECT_EQ(r.carriage_reversals, 0);
  EXPECT_EQ(r.spindle_reversals, 0);
  EXPECT_TRUE(r.eye_radius_by_hand);  // lathe2
}

// The clearance check's line: the program and line, the distance and the clearance; the question
// about the stops' eye radii on a lathe2 only (a lathe4's eye has its Y axis, no stop sets it).
TEST(Replay, ClearanceShortAsksForTheStopsEyeRadiusOnALathe2Only) {
  ReplayResult r;
  r.min_clearance = 16.3231;
  r.min_clearance_line = 8577;
  EXPECT_EQ(r.clearance_short("p.ngc", 20.0, 0.05, true),
            "p.ngc:8577: the replay puts the eye 16.323 mm from the surface of the layer in work, "
            "less than the clearance 20.000 mm");
  EXPECT_EQ(r.clearance_short("p.ngc", 20.0, 0.05, false),
            "machine.envelope.clearance: the replay of p.ngc puts the eye 16.323 mm from the "
            "surface of the layer in work at line 8577, less than the clearance 20.000 mm; no "
            "program written");
  r.eye_radius_by_hand = true;
  EXPECT_EQ(r.clearance_short("p.ngc", 20.0, 0.05, true),
            "p.ngc:8577: the replay puts the eye 16.323 mm from the surface of the layer in work, "
            "less than the clearance 20.000 mm (a lathe2 layup: does each layer's stop name its "
            "eye radius?)");
  r.min_clearance = 19.951;  // within chord_tolerance of the clearance
  EXPECT_EQ(r.clearance_short("p.ngc", 20.0, 0.05, true), "");
}

// Two layers by hand: a helix on the mandrel cylinder R, then (after a G0 that ties the tow on
// again) a helix at another angle on the cylinder R2 = R + 5 the first layer built. Each block
// follows the closed form of its own cylinder (helix_program's lead: beta = acos(R / R_e)).
TEST(Replay, EachCircuitIsWalkedOnTheSurfaceItWasWoundOn) {
  const double R = 50, R2 = 55, Re = 75, turns = 2;
  const double a1 = 60, a2 = 45;  // deg
  WindingPlan plan = test::helix_plan(R, a1, turns, 2000);
  Circuit outer = test::helix_plan(R2, a2, turns, 2000).circuits.front();
  outer.index = 1;
  plan.circuits.push_back(outer);
  const double c1 = R / std::tan(a1 * M_PI / 180), c2 = R2 / std::tan(a2 * M_PI / 180);
  const double len = std::max(c1, c2) * turns * 2 * M_PI + 100;
  const Mesh mandrel(test::open_cylinder(R, len, 512, 200));
  const Mesh built(test::open_cylinder(R2, len, 512, 200));
  std::string text = "%\n(two layers)\nG21 G90 G93\n";
  int outer_line = 0;
  for (int layer = 0; layer < 2; ++layer) {
    const double r = layer == 0 ? R : R2, c = layer == 0 ? c1 : c2;
    const double beta = std::acos(r / Re);
    if (layer == 1) outer_line = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    for (int i = 0; i < 1500; ++i) {
      const double phi = turns * 2 * M_PI * i / 1499;
      char buf[128];
      std::snprintf(buf, sizeof buf, "%s X%.4f A%.4f%s\n", i == 0 ? "G0" : "G1",
                    c * phi + c * std::tan(beta), -(phi + beta) * 180 / M_PI,
                    i == 0 ? "" : " F600");
      text += buf;
    }
  }
  text += "M2\n%\n";
  const MachineOptions m = lathe2(Re);
  const GcodeProgram p = read_gcode(text, m, "layers.ngc");
  // Each circuit on its own surface: both helices laid as planned.
  const ReplayResult own = replay_program(p, plan, mandrel, m, {}, {nullptr, &built});
  std::printf("own surfaces: %s\n", own.summary.c_str());
  EXPECT_LT(own.max_deviation, 0.05);
  EXPECT_NEAR(own.min_clearance, Re - R2, 0.01);  // the eye over the outer layer's surface
  // The bare mandrel under both (the default): the outer layer is laid on R, at least R2 - R from
  // its plan.
  const ReplayResult bare = replay_program(p, plan, mandrel, m);
  std::printf("bare mandrel: %s\n", bare.summary.c_str());
  EXPECT_GE(bare.max_deviation, R2 - R - 1e-6);
  EXPECT_GE(bare.max_deviation_line, outer_line);
  // A list shorter than the circuits, or null entries, is the mandrel: the same replay.
  const ReplayResult none = replay_program(p, plan, mandrel, m, {}, {nullptr});
  EXPECT_EQ(none.max_deviation, bare.max_deviation);
  EXPECT_EQ(none.substeps, bare.substeps);
}

// A layup whose second layer starts where the first one ends: its first circuit begins right over
// the first layer's last point (2 mm out, on the surface the first layer built) with a turnaround
// (pins), and a second circuit follows half a turn round. Near the first layer's end the pins of
// the second layer's first circuit were within catch_distance along the plan, so the contact
// jumped onto them; the G0 between the layers then tied the tow on at the next circuit start after
// that, the second layer's second circuit, and the whole first circuit of the second layer was
// laid from the wrong place (the robot replay of pipe_robot_layup with its eyes 0.05 mm further
// out: 15.98 mm off). The tow is tied on at a layer's first point by the G0 only.
TEST(Replay, ALayersPinsDoNotCatchTheLayerBeforeIt) {
  const double R = 50, R2 = 52, Re = 75, turns = 2, turns2 = 1, a1 = 60, a2 = 50;  // mm, deg
  const double c1 = R / std::tan(a1 * M_PI / 180), c2 = R2 / std::tan(a2 * M_PI / 180);
  const double z_end = c1 * turns * 2 * M_PI, theta_end = turns * 2 * M_PI;
  WindingPlan plan = test::helix_plan(R, a1, turns, 2000);
  // Layer 2: helices on R2 running down from z_end, the first from over the first layer's end.
  const int n2 = 2000, held = 40;
  for (int k = 0; k < 2; ++k) {
    Circuit ci;
    ci.index = 1 + k;
    const double psi = theta_end + k * M_PI;
    for (int i = 0; i < n2; ++i) {
      FibrePoint fp = test::helix_point(R2, -c2, turns2 * 2 * M_PI * i / (n2 - 1), psi);
      fp.position.z() += z_end;
      ci.points.push_back(fp);
    }
    ci.segments.push_back({CircuitSegment::Kind::Turnaround, 0, held});
    ci.segments.push_back({CircuitSegment::Kind::Pass, held, n2 - 1});
    plan.circuits.push_back(ci);
  }
  plan.layers.resize(2);
  plan.layers[0].first_circuit = 0;
  plan.layers[0].circuit_count = 1;
  plan.layers[1].first_circuit = 1;
  plan.layers[1].circuit_count = 2;
  const double len = z_end + 100;
  const Mesh mandrel(test::open_cylinder(R, len, 512, 200));
  const Mesh built(test::open_cylinder(R2, len, 512, 200));
  // The program: the first two circuits' closed-form eyes on the cylinder Re (helix_program's
  // lead), a G0 before each layer.
  std::string text = "%\n(two layers, the second from where the first ends)\nG21 G90 G93\n";
  text += helix_blocks(R, Re, c1, turns, 0.0, 0.0);
  const int second_line = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  text += helix_blocks(R2, Re, -c2, turns2, theta_end, z_end);
  text += "M2\n%\n";
  const MachineOptions m = lathe2(Re);
  const GcodeProgram p = read_gcode(text, m, "layers.ngc");
  const ReplayResult r = replay_program(p, plan, mandrel, m, {}, {nullptr, &built, &built});
  std::printf("%s\n", r.summary.c_str());
  // The second layer's first circuit is laid from its own first point (the program ends there).
  EXPECT_LT(r.max_deviation, 0.1) << "at line " << r.max_deviation_line << " (second layer from "
                                  << second_line << ")";
}

// The first layer ends on a turnaround (pins) and the second is tied on 60 deg before that end,
// its eye short of its lead (the free fibre lifts off: the contact stays on the tie-on point). At
// the tie-on the contact is on the second layer's first point, which is also the end of the step
// from the first layer's last point: the deviation track's window
// reached one segment back onto that step and put the contact on the first layer's last pin,
// which then held it until the eye had passed it by acos(R / R_e) (a hoop's tie-on turn on the
// taper of a helical layer in the KR 16 cell: 4.11 mm off). The track stays in the layer: the
// second layer is laid from its own first point.
// The replay of that layup; `empty_first`: the second layer starts with a circuit of no points.
ReplayResult replay_tied_on_before_the_end(bool empty_first) {
  const double R = 50, R2 = 52, Re = 75, turns = 2, turns2 = 1, a1 = 60, a2 = 50;  // mm, deg
  const double c1 = R / std::tan(a1 * M_PI / 180), c2 = R2 / std::tan(a2 * M_PI / 180);
  const double z_end = c1 * turns * 2 * M_PI, theta_end = turns * 2 * M_PI;
  const double psi2 = theta_end - 60 * M_PI / 180;
  WindingPlan plan = test::helix_plan(R, a1, turns, 2000);
  plan.circuits[0].segments = {{CircuitSegment::Kind::Pass, 0, 1959},
                               {CircuitSegment::Kind::Turnaround, 1959, 1999}};
  Circuit ci;
  ci.index = 1;
  for (int i = 0; i < 2000; ++i) {
    FibrePoint fp = test::helix_point(R2, -c2, turns2 * 2 * M_PI * i / 1999, psi2);
    fp.position.z() += z_end;
    ci.points.push_back(fp);
  }
  ci.segments.push_back({CircuitSegment::Kind::Pass, 0, 1999});
  if (empty_first) {
    Circuit none;
    none.index = 1;
    plan.circuits.push_back(none);
    ci.index = 2;
  }
  plan.circuits.push_back(ci);
  plan.layers.resize(2);
  plan.layers[0].circuit_count = 1;
  plan.layers[1].first_circuit = 1;
  plan.layers[1].circuit_count = empty_first ? 2 : 1;
  const Mesh mandrel(test::open_cylinder(R, z_end + 100, 512, 200));
  const Mesh built(test::open_cylinder(R2, z_end + 100, 512, 200));
  std::string text =
      "%\n(two layers, the second tied on before the first one's end)\nG21 G90 G93\n";
  text += helix_blocks(R, Re, c1, turns, 0.0, 0.0);
  // The second layer's eye starts 5 % short of its lead: the free fibre lifts off its first point.
  text += helix_blocks(R2, Re, -c2, turns2, psi2, z_end, 0.05);
  text += "M2\n%\n";
  const MachineOptions m = lathe2(Re);
  const ReplayResult r = replay_program(read_gcode(text, m, "layers.ngc"), plan, mandrel, m, {},
                                        {nullptr, &built, &built});
  std::printf("%s\n", r.summary.c_str());
  return r;
}

TEST(Replay, ATieOnStartsFromTheLayersFirstPoint) {
  const ReplayResult r = replay_tied_on_before_the_end(false);
  // 0.201 mm (the contact catching up as the eye takes up its lead); 5.28 mm with the track's
  // window reaching back, 42.5 mm with it bounded at the layer's end only.
  EXPECT_LT(r.max_deviation, 0.5) << "at line " << r.max_deviation_line;
}

// The same layup with a circuit of no points first in the second layer (WindingPlan allows
// them; compute_motion skips them): the layer's tie-on is its first circuit with points, and
// the replay is the same. (Before, a layer whose first circuit had no points had no tie-on: the
// two layers were tracked as one stretch and the tow tied on at no layer.)
TEST(Replay, ALayerStartingWithAnEmptyCircuitIsTiedOnAtItsFirstPoint) {
  const ReplayResult with_empty = replay_tied_on_before_the_end(true);
  const ReplayResult plain = replay_tied_on_before_the_end(false);
  EXPECT_EQ(with_empty.max_deviation, plain.max_deviation);
  EXPECT_EQ(with_empty.max_deviation_line, plain.max_deviation_line);
  EXPECT_LT(with_empty.max_deviation, 0.5) << "at line " << with_empty.max_deviation_line;
}

TEST(Replay, OneMillimetreCarriageFaultIsCaught) {
  const double R = 50, Re = 70, alpha = 60, turns = 2;
  const WindingPlan plan = test::helix_plan(R, alpha, turns, 2000);
  const double c = R / std::tan(alpha * M_PI / 180);
  const Mesh mesh(test::open_cylinder(R, c * turns * 2 * M_PI + 100, 512, 200));
  const MachineOptions m = lathe2(Re);
  const GcodeProgram p = read_gcode(helix_program(R, Re, c, turns, 1500, 1.0, 500), m, "fault.ngc");
  const ReplayResult r = replay_program(p, plan, mesh, m);
  std::printf("%s\n", r.summary.c_str());
  // An axial shift of 1 mm moves a helix at 60 deg to the axis by sin(60 deg) = 0.87 mm.
  EXPECT_GT(r.max_deviation, 0.8);
  EXPECT_LT(r.max_deviation, 1.05);
  EXPECT_GT(r.max_deviation_line, 500);
  // machine.replay_tolerance (ReplayResult::within): 0.5 mm refuses it, naming the line; 2 mm and
  // 0 (report only) let it pass.
  ReplayExcess e;
  EXPECT_TRUE(r.within(2.0, &e));
  EXPECT_TRUE(r.within(0.0, &e));
  ASSERT_FALSE(r.within(0.5, &e));
  EXPECT_FALSE(e.eye);
  EXPECT_EQ(e.line, r.max_deviation_line);
  char dev[80];
  std::snprintf(dev, sizeof dev, "%.3f mm from the plan", r.max_deviation);
  const std::string line = std::to_string(r.max_deviation_line);
  EXPECT_EQ(e.refused("toolpath.ngc"),
            "machine.replay_tolerance: the replay of toolpath.ngc lays "
            "the fibre " +
                std::string(dev) + " at line " + line + ", more than 0.500 mm; no program written");
  EXPECT_EQ(e.located("fault.ngc"), "fault.ngc:" + line + ": the replay lays the fibre " + dev +
                                        ", more than machine.replay_tolerance 0.500 mm");
}

// Issue 28: a spindle jump of 1e9 deg was cut into fixed 0.5 mm sub-steps (hours); bounded by
// the eye's travel before any sub-stepping, with the line named.
TEST(Replay, AnAbsurdJumpIsRefusedBeforeSubStepping) {
  const double R = 50, Re = 70, alpha = 60, turns = 2;
  const WindingPlan plan = test::helix_plan(R, alpha, turns, 2000);
  const double c = R / std::tan(alpha * M_PI / 180);
  const Mesh mesh(test::open_cylinder(R, c * turns * 2 * M_PI + 100, 512, 200));
  const MachineOptions m = lathe2(Re);
  std::string text = helix_program(R, Re, c, turns, 100);
  const std::size_t at = text.find("G1 ", text.find("G1 ") + 1);  // the second move: line 5
  text.insert(at, "G1 X40 A-1000000000 F600\n");
  const GcodeProgram p = read_gcode(text, m, "jump.ngc");
  try {
    replay_program(p, plan, mesh, m);
    FAIL() << "a 1e9 deg jump was replayed";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("program line 6: the eye travels 1.222e+09 mm in one move"),
        std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace windplan
