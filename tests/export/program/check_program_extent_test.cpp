#include "export/program/check_program_extent.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/export/plan_fixtures.h"

namespace windplan {
namespace {

GcodeBlock block(int line, double a, double x, double y, double eye_radius = 0.0,
                 bool rapid = false) {
  GcodeBlock b;
  b.line = line;
  b.a = a;
  b.x = x;
  b.y = y;
  b.eye_radius = eye_radius;
  b.rapid = rapid;
  return b;
}

std::string message_of(const GcodeProgram& p, const WindingPlan& plan, const MachineOptions& m,
                       const ProgramExtentOptions& o = {}) {
  try {
    check_program_extent(p, plan, Mesh(), m, "t.ngc", o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The eye's travel in closed form: a full turn of A at radius 100 (chord 0, arc 2 pi 100), then
// 30 mm along X, then a rapid move that does not count.
TEST(CheckProgramExtent, TravelIsTheArcAndTheChordOfEachFeedMove) {
  MachineOptions m;
  m.kind = "lathe4";
  GcodeProgram p;
  p.blocks = {block(1, 0, 0, 100), block(2, 360, 0, 100), block(3, 360, 30, 100),
              block(4, 0, -500, 100, 0.0, true)};
  const WindingPlan plan;
  const ProgramExtent e = check_program_extent(p, plan, Mesh(), m, "t.ngc");
  EXPECT_NEAR(e.eye_travel_mm, 2 * M_PI * 100 + 30, 1e-9);
  // Bounded: the line where the travel passes the bound is named.
  ProgramExtentOptions o;
  o.max_travel_mm = 600;
  EXPECT_NE(message_of(p, plan, m, o).find("t.ngc:2: the eye has travelled more than"),
            std::string::npos);
  o.max_travel_mm = 650;
  EXPECT_NE(message_of(p, plan, m, o).find("t.ngc:3:"), std::string::npos);
  o.max_travel_mm = 0;
  EXPECT_THROW(check_program_extent(p, plan, Mesh(), m, "t.ngc", o), ConfigError);
}

// lathe2: the k-th stop comes before layer k + 1 and must set the eye outside that layer's
// surface; its radius is the eye's for the moves after it (a quarter turn at 80 mm: the chord
// 80 sqrt(2) and the arc 40 pi).
TEST(CheckProgramExtent, Lathe2StopsLieOutsideTheLayerAfterThem) {
  MachineOptions m;
  m.kind = "lathe2";
  WindingPlan plan = test::helix_plan(40, 50, 1, 50);
  plan.layers.resize(2);
  plan.layers[0].name = "inner";
  plan.layers[0].surface_radius = 40;
  plan.layers[1].name = "outer";
  plan.layers[1].surface_radius = 45.5;
  GcodeProgram p;
  p.blocks = {block(5, 0, 0, 0, 80), block(6, 90, 0, 0, 80)};
  p.eye_stops = {{4, 80}};
  EXPECT_NEAR(check_program_extent(p, plan, Mesh(), m, "t.ngc").eye_travel_mm,
              std::hypot(80 * std::sqrt(2.0), 40 * M_PI), 1e-9);
  p.eye_stops = {{4, 45.5}};
  EXPECT_NE(message_of(p, plan, m)
                .find("t.ngc:4: the stop sets the eye at radius 45.5 mm, inside the part: layer "
                      "2 (outer) is wound on a surface reaching radius 45.50 mm"),
            std::string::npos)
      << message_of(p, plan, m);
  // A stop beyond the last layer: the outermost surface.
  p.eye_stops = {{4, 80}, {9, 42}};
  EXPECT_NE(message_of(p, plan, m)
                .find("t.ngc:9: the stop sets the eye at radius 42 mm, inside "
                      "the part: the outermost layer's surface reaches radius "
                      "45.50 mm"),
            std::string::npos)
      << message_of(p, plan, m);
}

}  // namespace
}  // namespace windplan
