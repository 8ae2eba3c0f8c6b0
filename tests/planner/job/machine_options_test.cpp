#include "planner/job/machine_options.h"

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "planner/job/job.h"

namespace windplan {
namespace {

const std::string kMandrel = "mandrel:\n  file: a.obj\n";

std::string error_of(const std::string& yaml) {
  try {
    load_job_from_string(kMandrel + yaml, "/jobs/m.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(MachineOptions, DefaultsAreValid) {
  std::string why;
  EXPECT_TRUE(MachineOptions{}.is_valid(&why)) << why;
  EXPECT_EQ(MachineOptions{}.envelope.mode(), "clearance");
  const Job job = load_job_from_string(kMandrel, "/jobs/m.yaml");
  EXPECT_EQ(job.machine.kind, "lathe2");
  EXPECT_TRUE(job.output.csv);
  EXPECT_FALSE(job.output.timings);
}

TEST(MachineOptions, DecodesEverySection) {
  const Job job = load_job_from_string(kMandrel +
                                           "machine:\n"
                                           "  kind: lathe4\n"
                                           "  chord_tolerance: 0.1\n"
                                           "  max_fibre_speed: 250\n"
                                           "  envelope:\n"
                                           "    profile: [[0, 80], [500, 90.5]]\n"
                                           "  axes:\n"
                                           "    A: {letter: C, sign: -1, max_velocity: 1080}\n"
                                           "    X: {min: -10, max: 1500, offset: 5}\n"
                                           "  gcode:\n"
                                           "    dialect: fanuc\n"
                                           "    feed: inverse_time\n"
                                           "    program_number: 2000\n"
                                           "output:\n"
                                           "  directory: out/run1\n"
                                           "  svg: false\n"
                                           "  timings: true\n",
                                       "/jobs/m.yaml");
  const MachineOptions& m = job.machine;
  EXPECT_EQ(m.kind, "lathe4");
  EXPECT_DOUBLE_EQ(m.chord_tolerance, 0.1);
  EXPECT_DOUBLE_EQ(m.max_fibre_speed, 250);
  ASSERT_EQ(m.envelope.profile.size(), 2u);
  EXPECT_DOUBLE_EQ(m.envelope.profile[1][1], 90.5);
  EXPECT_EQ(m.envelope.mode(), "profile");
  EXPECT_EQ(m.a.letter, "C");
  EXPECT_DOUBLE_EQ(m.a.sign, -1);
  EXPECT_DOUBLE_EQ(m.a.max_velocity, 1080);
  EXPECT_DOUBLE_EQ(m.x.max, 1500);
  EXPECT_DOUBLE_EQ(m.x.offset, 5);
  EXPECT_EQ(m.gcode.dialect, "fanuc");
  EXPECT_EQ(m.gcode.feed, "inverse_time");
  EXPECT_EQ(m.gcode.program_number, 2000);
  EXPECT_EQ(job.output.directory, std::filesystem::path("/jobs/out/run1"));
  EXPECT_FALSE(job.output.svg);
  EXPECT_TRUE(job.output.timings);
}

TEST(MachineOptions, UnknownKeysNameFileLineAndKey) {
  std::string e = error_of("machine:\n  kind: lathe2\n  clearence: 3\n");
  EXPECT_NE(e.find("/jobs/m.yaml:5"), std::string::npos) << e;
  EXPECT_NE(e.find("machine.clearence"), std::string::npos) << e;
  e = error_of("machine:\n  envelope:\n    clearance: 5\n    profil: [[0, 1]]\n");
  EXPECT_NE(e.find("/jobs/m.yaml:6"), std::string::npos) << e;
  EXPECT_NE(e.find("machine.envelope.profil"), std::string::npos) << e;
  e = error_of("machine:\n  axes:\n    X:\n      max_speed: 3\n");
  EXPECT_NE(e.find("/jobs/m.yaml:6"), std::string::npos) << e;
  EXPECT_NE(e.find("machine.axes.X.max_speed"), std::string::npos) << e;
  e = error_of("machine:\n  axes:\n    Q: {letter: Q}\n");
  EXPECT_NE(e.find("machine.axes.Q"), std::string::npos) << e;
  e = error_of("output:\n  svgs: false\n");
  EXPECT_NE(e.find("/jobs/m.yaml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("output.svgs"), std::string::npos) << e;
}

TEST(MachineOptions, BadValuesNameTheKey) {
  std::string e = error_of("machine:\n  envelope:\n    clearance: -5\n");
  EXPECT_NE(e.find("clearance"), std::string::npos) << e;
  EXPECT_NE(e.find("machine.envelope"), std::string::npos) << e;
  e = error_of("machine:\n  gcode:\n    dialect: haas\n");
  EXPECT_NE(e.find("machine.gcode.dialect"), std::string::npos) << e;
  EXPECT_NE(e.find("haas"), std::string::npos) << e;
  e = error_of("machine:\n  kind: hexapod\n");
  EXPECT_NE(e.find("machine.kind"), std::string::npos) << e;
  e = error_of("machine:\n  envelope:\n    profile: [[0, 50], [0, 60]]\n");
  EXPECT_NE(e.find("increase"), std::string::npos) << e;
  e = error_of("machine:\n  envelope:\n    profile: [[0, 50], [1]]\n");
  EXPECT_NE(e.find("machine.envelope.profile"), std::string::npos) << e;
  e = error_of("machine:\n  envelope:\n    clearance: 5\n    free_length: 100\n");
  EXPECT_NE(e.find("only one"), std::string::npos) << e;
  e = error_of("machine:\n  axes:\n    A: {max_velocity: 0}\n");
  EXPECT_NE(e.find("max_velocity"), std::string::npos) << e;
  EXPECT_NE(e.find("machine.axes.A"), std::string::npos) << e;
  e = error_of("machine:\n  axes:\n    Y: {letter: X}\n  kind: lathe4\n");
  EXPECT_NE(e.find("share the letter"), std::string::npos) << e;
  e = error_of("machine:\n  gcode: {dialect: marlin, feed: inverse_time}\n");
  EXPECT_NE(e.find("G93"), std::string::npos) << e;
  e = error_of("machine:\n  chord_tolerance: 0\n");
  EXPECT_NE(e.find("chord_tolerance"), std::string::npos) << e;
}

}  // namespace
}  // namespace windplan
