// The closest-point hierarchy against brute force (every face tried) on a torus and a rough torus,
// and closest_within's bound: below the distance it finds nothing, above it the same hit as
// closest(), bit for bit.
#include "geometry/mesh/closest_point.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

double brute_force_distance2(const Mesh& mesh, const Vec3& q, int* face) {
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Tri& t = mesh.triangle(f);
    Vec3 b;
    const double d2 = (closest_point_on_triangle(q, mesh.position(t[0]), mesh.position(t[1]),
                                                 mesh.position(t[2]), &b) -
                       q)
                          .squaredNorm();
    if (d2 < best) {
      best = d2;
      *face = f;
    }
  }
  return best;
}

// Points round the torus (R 30, r 10, centred on the origin, axis z): inside the tube, on it
// and up to 25 mm out, as the replay's contact walk and the clearance eye ask.
std::vector<Vec3> query_points(unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * u(rng), b = 2 * M_PI * u(rng), rho = 35.0 * u(rng);
    out.emplace_back((30 + rho * std::cos(b)) * std::cos(a), (30 + rho * std::cos(b)) * std::sin(a),
                     rho * std::sin(b));
  }
  return out;
}

void expect_same_hit(const ClosestPointQuery::Hit& a, const ClosestPointQuery::Hit& b,
                     const std::string& what) {
  EXPECT_EQ(a.point.element, b.point.element) << what;
  EXPECT_EQ(a.point.bary, b.point.bary) << what;
  EXPECT_EQ(a.position, b.position) << what;
  EXPECT_EQ(a.distance, b.distance) << what;
}

TEST(ClosestPoint, TheHierarchyFindsWhatEveryFaceTriedFinds) {
  for (const Mesh& mesh : {Mesh(test::torus(30, 10, 48, 24)), Mesh(test::rough_torus(0.5, 3))}) {
    const ClosestPointQuery query(mesh);
    for (const Vec3& q : query_points(11, 400)) {
      int face = -1;
      const double d2 = brute_force_distance2(mesh, q, &face);
      const ClosestPointQuery::Hit h = query.closest(q);
      ASSERT_GE(h.point.element, 0);
      EXPECT_NEAR(h.distance, std::sqrt(d2), 1e-12 * (1.0 + std::sqrt(d2)));
      EXPECT_NEAR((h.position - q).norm(), h.distance, 1e-12);
      // The barycentric coordinates place the hit on its face.
      const Tri& t = mesh.triangle(h.point.element);
      const Vec3 back = h.point.bary[0] * mesh.position(t[0]) +
                        h.point.bary[1] * mesh.position(t[1]) +
                        h.point.bary[2] * mesh.position(t[2]);
      EXPECT_LT((back - h.position).norm(), 1e-9);
    }
  }
}

TEST(ClosestPoint, ABoundBelowTheDistanceFindsNothingAndOneAboveFindsTheSameHit) {
  const Mesh mesh(test::torus(30, 10, 48, 24));
  const ClosestPointQuery query(mesh);
  for (const Vec3& q : query_points(12, 200)) {
    const ClosestPointQuery::Hit h = query.closest(q);
    if (!(h.distance > 1e-6)) continue;
    const ClosestPointQuery::Hit below = query.closest_within(q, 0.98 * h.distance * h.distance);
    EXPECT_EQ(below.point.element, -1);
    EXPECT_EQ(below.distance, std::numeric_limits<double>::infinity());
    expect_same_hit(query.closest_within(q, 1.02 * h.distance * h.distance), h, "bounded");
  }
}

TEST(ClosestPoint, AnEmptyMeshHasNoClosestPoint) {
  const Mesh mesh{TriangleSoup{}};
  const ClosestPointQuery query(mesh);
  EXPECT_EQ(query.closest(Vec3(1, 2, 3)).point.element, -1);
  EXPECT_EQ(query.closest(Vec3(1, 2, 3)).distance, std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace windplan
