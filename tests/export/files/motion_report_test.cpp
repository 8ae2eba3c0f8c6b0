// The motion section of the reports (export/files/motion_report.h): report.md names what the
// clearance figure measures, the mandrel or, on a layup, the layer in work
// (Motion::clearance_on_layers), and says "not checked" without a mesh.
#include "export/files/motion_report.h"

#include <gtest/gtest.h>

#include <string>

namespace windplan {
namespace {

TEST(MotionReport, ClearanceLabelNamesTheSurfaceItIsMeasuredOn) {
  Motion mo;
  mo.min_clearance = 20.0421;
  mo.required_clearance = 20.0;
  const std::string mandrel = motion_markdown(mo, nullptr);
  EXPECT_NE(mandrel.find("| min eye-mandrel distance | 20.042 mm (required 20.000 mm) |"),
            std::string::npos)
      << mandrel;
  EXPECT_EQ(mandrel.find("layer in work"), std::string::npos) << mandrel;
  mo.clearance_on_layers = true;
  const std::string layers = motion_markdown(mo, nullptr);
  EXPECT_NE(
      layers.find("| min eye distance from the layer in work | 20.042 mm (required 20.000 mm) |"),
      std::string::npos)
      << layers;
  EXPECT_EQ(layers.find("eye-mandrel"), std::string::npos) << layers;
  // The JSON key stays neutral (min_clearance_mm): the same for both.
  JsonWriter a, b;
  mo.clearance_on_layers = false;
  motion_json(a.begin_object(), mo, nullptr);
  a.end_object();
  mo.clearance_on_layers = true;
  motion_json(b.begin_object(), mo, nullptr);
  b.end_object();
  EXPECT_EQ(a.str(), b.str());
  EXPECT_NE(a.str().find("\"min_clearance_mm\": 20.0421"), std::string::npos) << a.str();
}

TEST(MotionReport, NoMeshIsNotChecked) {
  const Motion mo;  // min_clearance NaN
  EXPECT_NE(motion_markdown(mo, nullptr).find("| min eye-mandrel distance | not checked |"),
            std::string::npos);
}

}  // namespace
}  // namespace windplan
