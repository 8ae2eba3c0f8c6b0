// Tests for planner/girth/girth.h: the exact girth against closed forms (cylinder, cone, the neck
// of a surface of revolution), the interpolated field against direct evaluation at held-out
// vertices, and bad input.
#include "planner/girth/girth.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/mesh/surface_path.h"
#include "planner/job/job.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

std::array<std::vector<int>, 2> ring_loops(int n, int m) { return test::revolution_loops(n, m); }

double polygon_perimeter(double r, int n) { return n * 2.0 * r * std::sin(M_PI / n); }

// ---- exact girth: closed forms ----

TEST(GirthAt, CylinderRingIsThePolygonPerimeter) {
  const int n = 48, m = 16;
  const double r = 10.0, len = 20.0;
  const Mesh mesh(test::open_cylinder(r, len, n, m));
  const auto loops = ring_loops(n, m);
  const double expected = polygon_perimeter(r, n);
  const GirthContext context(mesh, loops);
  for (int v : {8 * n + 5, 3 * n + 17, 13 * n, 0, m * n + 31}) {  // interior and boundary
    const GirthContext::Loop loop = context.girth(v);
    EXPECT_NEAR(loop.girth, expected, 1e-6 * expected) << "vertex " << v;
    EXPECT_EQ(std::abs(loop.winding), 1) << "vertex " << v;
    EXPECT_TRUE(loop.converged) << "vertex " << v;
    std::string why;
    EXPECT_TRUE(is_valid_path(mesh, loop.path, &why)) << why;
    ASSERT_EQ(loop.path.start.kind, SurfacePoint::Kind::Vertex);
    EXPECT_EQ(loop.path.start.element, v);
    EXPECT_EQ(loop.path.end.element, v);
    // The loop stays on the ring of p (z constant).
    for (const Vec3& q : polyline(mesh, loop.path)) {
      EXPECT_NEAR(q.z(), mesh.position(v).z(), 1e-6);
    }
  }
  SurfacePath out;
  EXPECT_NEAR(girth_at(mesh, loops, 8 * n + 5, &out), expected, 1e-6 * expected);
  EXPECT_NEAR(euclidean_length(mesh, out), expected, 1e-6 * expected);
}

// Cone frustum of half-angle b (sin b = (r0 - r1) / slant). Unrolled, the polyhedral cone is a
// flat sector of angle T = n * 2 asin(sin b sin(pi / n)) (n isosceles slices from the apex), and a
// vertex at slant distance s from the apex has the chord 2 s sin(T / 2) as its shortest loop, as
// long as the chord stays on the frustum (s cos(T / 2) >= slant distance of the small end) and
// T < pi. The smooth cone has T = 2 pi sin b: g = 2 r sin(pi sin b) / sin b.
TEST(GirthAt, ConeMatchesTheUnrolledChord) {
  const int n = 256, m = 100;
  const double r0 = 60.0, r1 = 40.0, len = 400.0;
  const Mesh mesh(
      test::revolution([&](double z) { return r0 + (r1 - r0) * z / len; }, 0.0, len, n, m));
  const auto loops = ring_loops(n, m);
  const double sin_b = (r0 - r1) / std::hypot(r0 - r1, len);
  const double sector = n * 2.0 * std::asin(sin_b * std::sin(M_PI / n));
  ASSERT_LT(sector, M_PI);
  const GirthContext context(mesh, loops);
  for (int j : {0, 10, 25, 40}) {
    const double r = r0 + (r1 - r0) * double(j) / m;
    const double s = r / sin_b;
    ASSERT_GE(s * std::cos(sector / 2), r1 / sin_b);  // the chord stays on the frustum
    const int v = j * n + (7 * j) % n;
    const GirthContext::Loop loop = context.girth(v);
    const double discrete = 2.0 * s * std::sin(sector / 2);
    const double smooth = 2.0 * r * std::sin(M_PI * sin_b) / sin_b;
    EXPECT_NEAR(loop.girth, discrete, 1e-6 * discrete) << "ring " << j;
    EXPECT_NEAR(loop.girth, smooth, 1e-3 * smooth) << "ring " << j;
    // Not a ring: strictly shorter than the circle through p.
    EXPECT_LT(loop.girth, polygon_perimeter(r, n) * (1.0 - 1e-3));
    EXPECT_EQ(std::abs(loop.winding), 1);
  }
}

// r(z) = 10 (1 + 0.3 sin(z / 10)) between two maxima: the neck circle (r = 7) is the shortest
// loop through any of its points (every loop winding once is at least 2 pi r_min long). The 1-D
// reference for points off the neck (Clairaut) is not computed: only the neck is tested here.
TEST(GirthAt, NeckOfASurfaceOfRevolution) {
  const int n = 128, m = 64;
  const double z0 = 10.0 * M_PI / 2, z1 = 10.0 * 5 * M_PI / 2;  // neck at the middle ring
  const Mesh mesh(test::revolution([](double z) { return 10.0 * (1.0 + 0.3 * std::sin(z / 10.0)); },
                                   z0, z1, n, m));
  const auto loops = ring_loops(n, m);
  const double expected = polygon_perimeter(7.0, n);
  const GirthContext context(mesh, loops);
  for (int i : {0, 19, 64, 101}) {
    const int v = (m / 2) * n + i;
    ASSERT_NEAR(std::hypot(mesh.position(v).x(), mesh.position(v).y()), 7.0, 1e-12);
    const GirthContext::Loop loop = context.girth(v);
    EXPECT_NEAR(loop.girth, expected, 1e-3 * expected) << "vertex " << v;
    EXPECT_GE(loop.girth, expected * (1.0 - 1e-9));
    EXPECT_EQ(std::abs(loop.winding), 1);
  }
  // Off the neck the loop through p is longer than the neck and shorter than p's own circle.
  const int v = (m / 4) * n + 3;
  const double r = std::hypot(mesh.position(v).x(), mesh.position(v).y());
  const double g = context.girth(v).girth;
  EXPECT_GT(g, expected);
  EXPECT_LE(g, polygon_perimeter(r, n) * (1.0 + 1e-9));
}

// ---- the field ----

// Direct evaluation at held-out vertices: the interpolated value is close and within the bound.
void check_held_out(const Mesh& mesh, const std::array<std::vector<int>, 2>& loops,
                    const GirthField& field, double max_relative) {
  ASSERT_EQ(field.vertex_girth.size(), static_cast<std::size_t>(mesh.num_vertices()));
  std::set<int> sampled;
  for (const GirthSample& s : field.samples) sampled.insert(s.vertex);
  const GirthContext context(mesh, loops);
  int checked = 0;
  double worst = 0.0;
  for (int v = 7; v < mesh.num_vertices(); v += mesh.num_vertices() / 23) {
    if (sampled.count(v)) continue;
    const double exact = context.girth(v).girth;
    const double interp = field.vertex_girth[v];
    worst = std::max(worst, std::abs(interp - exact) / exact);
    EXPECT_LE(std::abs(interp - exact), field.lipschitz_bound) << "vertex " << v;
    EXPECT_LE(std::abs(interp - exact), max_relative * exact) << "vertex " << v;
    ++checked;
  }
  EXPECT_GE(checked, 15);
  std::cout << "[ field    ] " << field.samples.size() << " samples, bound "
            << field.lipschitz_bound << " mm, held-out max relative error " << worst << "\n";
  for (const GirthSample& s : field.samples) {
    EXPECT_DOUBLE_EQ(field.vertex_girth[s.vertex], s.girth);
    EXPECT_EQ(s.position, mesh.position(s.vertex));
  }
}

TEST(GirthField, CylinderIsConstant) {
  const int n = 40, m = 30;
  const Mesh mesh(test::open_cylinder(10.0, 40.0, n, m));
  const auto loops = ring_loops(n, m);
  GirthOptions options;
  options.samples = 16;
  const GirthField field = compute_girth_field(mesh, loops, options);
  EXPECT_EQ(field.samples.size(), 16u);
  EXPECT_EQ(field.unconverged_samples, 0);
  const double expected = polygon_perimeter(10.0, n);
  for (double g : field.vertex_girth) ASSERT_NEAR(g, expected, 1e-6 * expected);
  const std::vector<double> fg = field.face_girth(mesh);
  ASSERT_EQ(fg.size(), static_cast<std::size_t>(mesh.num_faces()));
  for (double g : fg) ASSERT_NEAR(g, expected, 1e-6 * expected);
  // 4 rings of 4 over 40 mm: some vertex is several mm from every sample.
  EXPECT_GT(field.lipschitz_bound, 5.0);
  EXPECT_LT(field.lipschitz_bound, 2.0 * 40.0);
  EXPECT_GT(field.time_ms, 0.0);
}

TEST(GirthField, ConeRingsAgainstDirectEvaluation) {
  const int n = 96, m = 40;
  const double r0 = 60.0, r1 = 40.0, len = 400.0;
  const Mesh mesh(
      test::revolution([&](double z) { return r0 + (r1 - r0) * z / len; }, 0.0, len, n, m));
  const auto loops = ring_loops(n, m);
  const GirthField field = compute_girth_field(mesh, loops, GirthOptions{});
  EXPECT_EQ(field.samples.size(), 64u);
  EXPECT_EQ(field.unconverged_samples, 0);
  check_held_out(mesh, loops, field, 0.01);
}

TEST(GirthField, NeckFarthestAgainstDirectEvaluation) {
  const int n = 64, m = 40;
  const Mesh mesh(test::revolution([](double z) { return 10.0 * (1.0 + 0.3 * std::sin(z / 10.0)); },
                                   10.0 * M_PI / 2, 10.0 * 5 * M_PI / 2, n, m));
  const auto loops = ring_loops(n, m);
  GirthOptions options;
  options.placement = "farthest";
  options.samples = 48;
  const GirthField field = compute_girth_field(mesh, loops, options);
  EXPECT_EQ(field.samples.size(), 48u);
  check_held_out(mesh, loops, field, 0.05);
  // Farthest-point sampling leaves no vertex farther than the bound / 2 from a sample, and the
  // bound shrinks with more samples.
  options.samples = 96;
  const GirthField finer = compute_girth_field(mesh, loops, options);
  EXPECT_LT(finer.lipschitz_bound, field.lipschitz_bound);
}

// ---- bad input ----

TEST(GirthBadInput, NotAnAnnulus) {
  const Mesh disk(test::grid(4, 4));
  std::array<std::vector<int>, 2> loops{std::vector<int>{0}, std::vector<int>{24}};
  try {
    girth_at(disk, loops, 12);
    FAIL() << "a disk was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("1 boundary loop"), std::string::npos) << e.what();
  }
  const Mesh closed(test::octahedron());
  try {
    compute_girth_field(closed, {std::vector<int>{0}, std::vector<int>{1}});
    FAIL() << "a closed mesh was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("0 boundary loop"), std::string::npos) << e.what();
  }
}

TEST(GirthBadInput, OptionsAndArguments) {
  const int n = 12, m = 4;
  const Mesh mesh(test::open_cylinder(5.0, 5.0, n, m));
  const auto loops = ring_loops(n, m);
  GirthOptions options;
  options.samples = 3;
  std::string why;
  EXPECT_FALSE(options.is_valid(&why));
  EXPECT_NE(why.find("samples"), std::string::npos);
  EXPECT_THROW(compute_girth_field(mesh, loops, options), ConfigError);
  options.samples = 8;
  options.placement = "random";
  EXPECT_THROW(compute_girth_field(mesh, loops, options), ConfigError);
  options.placement = "rings";
  options.rings = -1;
  EXPECT_THROW(compute_girth_field(mesh, loops, options), ConfigError);
  EXPECT_THROW(girth_at(mesh, loops, mesh.num_vertices()), InputError);
  EXPECT_THROW(girth_at(mesh, loops, -1), InputError);
  EXPECT_THROW(girth_at(mesh, {loops[0], loops[0]}, 20), InputError);
  EXPECT_THROW(girth_at(mesh, {loops[0], std::vector<int>{20}}, 20), InputError);  // interior
  EXPECT_THROW(girth_at(mesh, {loops[0], std::vector<int>{}}, 20), InputError);
}

// ---- the girth: job section ----

constexpr const char* kPipeJob = "mandrel: {source: pipe, pipe: {radius: 50, length: 100}}\n";

TEST(GirthJob, SectionIsDecodedAndChecked) {
  const Job job = load_job_from_string(
      std::string(kPipeJob) + "girth:\n  samples: 40\n  placement: farthest\n  rings: 5\n",
      "job.yaml");
  EXPECT_EQ(job.girth.samples, 40);
  EXPECT_EQ(job.girth.placement, "farthest");
  EXPECT_EQ(job.girth.rings, 5);
  const Job defaults = load_job_from_string(kPipeJob, "job.yaml");
  EXPECT_EQ(defaults.girth.samples, 64);
  EXPECT_EQ(defaults.girth.placement, "rings");
  EXPECT_EQ(defaults.girth.rings, 0);
  auto error_of = [](const std::string& yaml) {
    try {
      load_job_from_string(kPipeJob + yaml, "job.yaml");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string unknown = error_of("girth:\n  sample: 10\n");
  EXPECT_NE(unknown.find("job.yaml:3:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("girth.sample"), std::string::npos) << unknown;
  EXPECT_NE(error_of("girth: {samples: 3}\n").find("samples"), std::string::npos);
  EXPECT_NE(error_of("girth: {placement: random}\n").find("placement"), std::string::npos);
  EXPECT_NE(error_of("girth: {rings: -2}\n").find("rings"), std::string::npos);
}

}  // namespace
}  // namespace windplan
