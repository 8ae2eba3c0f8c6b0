// Tube coordinates (geometry/region/spine.h): the centre line extracted from the sections of a
// synthetic bent tube (circular and oval sections, a 4r bend) against the exact centre line, the
// analytic spine's interpolation and projection, and a region that is not a tube refused.
#include "geometry/region/spine.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"
#include "tests/geometry/region/tube_fixtures.h"

namespace windplan {
namespace {

// Largest distance of the spine's points from the exact centre line, and the largest angle (deg)
// between its tangents and the exact tangents at the same arc length.
void compare(const test::BentTube& tube, const Spine& sp, double* dist, double* angle) {
  *dist = *angle = 0.0;
  for (std::size_t i = 0; i < sp.points.size(); ++i) {
    // The nearest exact centre point (dense search: independent of the spine's own arc length).
    double best = 1e300, at = 0;
    for (int k = 0; k <= 4000; ++k) {
      const double s = tube.length() * k / 4000;
      const double d = (tube.centre(s) - sp.points[i]).norm();
      if (d < best) best = d, at = s;
    }
    *dist = std::max(*dist, best);
    const double c = std::clamp(sp.tangents[i].dot(tube.tangent(at)), -1.0, 1.0);
    *angle = std::max(*angle, std::acos(c) * 180 / M_PI);
  }
}

TEST(Spine, ExtractedFromACircularBentTube) {
  test::BentTube tube;  // r 25 on a 100 mm bend: 4r
  const Mesh m = tube.mesh();
  const SpineResult r = extract_spine(m, tube.loops(), SpindleAxis{});
  double dist = 0, angle = 0;
  compare(tube, r.spine, &dist, &angle);
  // The 96-gon's centroid is the centre; sections cut 6.25 mm apart along a 100 mm bend.
  EXPECT_LT(dist, 0.05) << r.summary.brief_report();
  EXPECT_LT(angle, 1.0) << r.summary.brief_report();
  EXPECT_NEAR(r.spine.length(), tube.length(), 0.5);
  EXPECT_NEAR(r.summary.mean_radius, 25.0, 0.05);
  EXPECT_GT(r.summary.sections, 40);
}

TEST(Spine, ExtractedFromAnOvalBentTubeOnA3rBend) {
  test::BentTube tube;
  tube.a = 35;  // in the bend plane
  tube.b = 20;
  tube.bend = 3 * 35;
  const SpineResult r = extract_spine(tube.mesh(), tube.loops(), SpindleAxis{});
  double dist = 0, angle = 0;
  compare(tube, r.spine, &dist, &angle);
  EXPECT_LT(dist, 0.3) << r.summary.brief_report();
  EXPECT_LT(angle, 2.0) << r.summary.brief_report();
  EXPECT_NEAR(r.spine.length(), tube.length(), 1.0);
}

TEST(Spine, AnalyticPolylineInterpolatesAndProjects) {
  test::BentTube tube;
  std::vector<Vec3> pts;
  for (int k = 0; k <= 400; ++k) pts.push_back(tube.centre(tube.length() * k / 400));
  const Spine sp = spine_from_polyline(pts);
  EXPECT_NEAR(sp.length(), tube.length(), 0.01);
  for (double s : {10.0, 150.0, 250.0, 300.0}) {
    EXPECT_LT((sp.point(s) - tube.centre(s)).norm(), 0.01) << s;
    EXPECT_GT(sp.tangent(s).dot(tube.tangent(s)), std::cos(0.5 * M_PI / 180)) << s;
    // A surface point projects to its own station.
    double d = 0;
    EXPECT_NEAR(sp.project(tube.at(s, 1.0), &d), s, 0.1) << s;  // (chords of 1.4 mm)
    EXPECT_NEAR(d, 25.0, 0.01);
  }
  EXPECT_THROW(spine_from_polyline({Vec3::Zero()}), InputError);
  EXPECT_THROW(spine_from_polyline({Vec3::Zero(), Vec3::Zero()}), InputError);
}

TEST(Spine, ARegionThatIsNotATubeIsRefused) {
  // A tube that turns back on itself within less than its radius: the sections normal to the
  // centre line march out of it.
  test::BentTube tube;
  tube.bend = 20;  // tighter than the radius 25: the surface folds on the inside
  tube.angle = M_PI / 2;
  tube.per_mm = 1;
  SpineOptions o;
  o.step = 10;
  bool refused = false;
  try {
    const SpineResult r = extract_spine(tube.mesh(), tube.loops(), SpindleAxis{}, o);
    double dist = 0, angle = 0;
    compare(tube, r.spine, &dist, &angle);
    refused = dist > 2.0;  // (or it is caught by the distance to the true centre line)
  } catch (const TopologyError&) {
    refused = true;  // the folded surface is not even a manifold
  } catch (const InputError& e) {
    refused = std::string(e.what()).find("tube centre line") != std::string::npos;
  }
  EXPECT_TRUE(refused);
  SpineOptions bad;
  bad.step = -1;
  EXPECT_THROW(extract_spine(test::BentTube{}.mesh(), test::BentTube{}.loops(), SpindleAxis{}, bad),
               ConfigError);
}

}  // namespace
}  // namespace windplan
