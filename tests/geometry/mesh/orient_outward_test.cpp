// geometry/mesh/orient_outward.h: the capped signed volume of an open n-gon tube is the prism's,
// (n / 2) r^2 sin(2 pi / n) L, positive outward and negative inward; inward components (open
// tubes, closed meshes, a bent tube whatever its axis) are reversed, outward ones left alone.
#include "geometry/mesh/orient_outward.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

TriangleSoup reversed(TriangleSoup s) {
  for (Tri& t : s.triangles) std::swap(t[1], t[2]);
  return s;
}

double volume(const Mesh& m) { return capped_signed_volume(m, m.face_components(), 0); }

TEST(OrientOutward, CappedVolumeOfAnOpenTubeIsThePrismsWithTheSideAsSign) {
  const int n = 24;
  const double r = 50.0, len = 200.0;
  const double prism = 0.5 * n * r * r * std::sin(2.0 * M_PI / n) * len;
  const Mesh out(test::open_cylinder(r, len, n, 10));
  EXPECT_NEAR(volume(out), prism, 1e-9 * prism);
  const Mesh in(reversed(test::open_cylinder(r, len, n, 10)));
  EXPECT_NEAR(volume(in), -prism, 1e-9 * prism);
}

TEST(OrientOutward, AnInwardOpenTubeIsReversedAnOutwardOneKept) {
  const TriangleSoup tube = test::open_cylinder(50.0, 200.0, 36, 8);
  const OrientOutwardResult kept = orient_outward(Mesh(tube));
  EXPECT_EQ(kept.summary.flipped_faces, 0);
  EXPECT_EQ(kept.mesh.triangles(), tube.triangles);

  const OrientOutwardResult fixed = orient_outward(Mesh(reversed(tube)));
  EXPECT_EQ(fixed.summary.components, 1);
  EXPECT_EQ(fixed.summary.flipped_components, 1);
  EXPECT_EQ(fixed.summary.flipped_faces, 36 * 8 * 2);
  EXPECT_EQ(fixed.mesh.triangles(), tube.triangles);  // exactly the outward tube again
  EXPECT_EQ(fixed.summary.brief_report(),
            "1 of 1 component(s) pointed inward: 576 triangles reversed");
}

TEST(OrientOutward, AClosedMeshAndABentTubeAreTurnedOutward) {
  // A closed sphere, inward.
  const TriangleSoup sphere = test::uv_sphere(10.0, 24, 12);
  const OrientOutwardResult s = orient_outward(Mesh(reversed(sphere)));
  EXPECT_EQ(s.summary.flipped_components, 1);
  EXPECT_GT(volume(s.mesh), 0.0);
  // A quarter of a torus (an elbow), open at both ends, inward: no straight axis tells its side.
  const double big = 100.0, small = 20.0;
  const int n = 24, m = 16;
  TriangleSoup elbow;
  for (int i = 0; i <= m; ++i) {
    const double u = 0.5 * M_PI * i / m;
    for (int j = 0; j < n; ++j) {
      const double v = 2.0 * M_PI * j / n;
      elbow.points.emplace_back((big + small * std::cos(v)) * std::cos(u),
                                (big + small * std::cos(v)) * std::sin(u), small * std::sin(v));
    }
  }
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j, b = i * n + (j + 1) % n, c = a + n, d = b + n;
      elbow.triangles.push_back({a, c, b});  // (u, v) right-handed with the outward normal
      elbow.triangles.push_back({b, c, d});
    }
  }
  const Mesh e(elbow);
  const OrientOutwardResult as_is = orient_outward(e);
  const OrientOutwardResult flipped = orient_outward(Mesh(reversed(elbow)));
  // Exactly one of the two orientations is reversed, and both end outward: the same triangles.
  EXPECT_EQ(as_is.summary.flipped_components + flipped.summary.flipped_components, 1);
  EXPECT_EQ(as_is.mesh.triangles(), flipped.mesh.triangles());
  EXPECT_GT(volume(as_is.mesh), 0.0);
  // The quarter torus's volume (Pappus, pi r^2 * pi R / 2) less the caps' chord error.
  const double pappus = M_PI * small * small * 0.5 * M_PI * big;
  EXPECT_NEAR(volume(as_is.mesh), pappus, 0.03 * pappus);
  // And the outward normal at the outer equator points away from the torus's centre line.
  const Mesh& o = as_is.mesh;
  for (int f = 0; f < o.num_faces(); ++f) {
    const Vec3 c = o.face_centroid(f);
    const Vec3 centre_line(big * c.x() / std::hypot(c.x(), c.y()),
                           big * c.y() / std::hypot(c.x(), c.y()), 0.0);
    EXPECT_GT(o.face_normal(f).dot(c - centre_line), 0.0) << "face " << f;
  }
}

TEST(OrientOutward, AFlatSheetIsLeftUndecided) {
  const OrientOutwardResult g = orient_outward(Mesh(test::grid(4, 4)));
  EXPECT_EQ(g.summary.undecided, 1);
  EXPECT_EQ(g.summary.flipped_faces, 0);
  OrientOutwardOptions bad;
  bad.volume_tolerance = -1.0;
  EXPECT_THROW(orient_outward(Mesh(test::grid(2, 2)), bad), ConfigError);
}

}  // namespace
}  // namespace windplan
