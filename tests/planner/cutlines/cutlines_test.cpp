// Coplanar cut-lines (planner/cutlines/cutlines.h): closed-form loops on a tessellated cylinder,
// the circular cross-section in the bend of a bent tube, open coplanar curves, and bad input.
#include "planner/cutlines/cutlines.h"

#include <cmath>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/cad/parametric_mandrel.h"
#include "geometry/mesh/closest_point.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

constexpr double kR = 50.0, kLen = 200.0;
constexpr int kN = 48, kM = 20;  // vertices around, rings of quads

const Mesh& cylinder() {
  static const Mesh m(test::open_cylinder(kR, kLen, kN, kM));
  return m;
}
SpindleAxis z_axis() { return SpindleAxis{}; }
double ring_perimeter(double r, int n) { return n * 2.0 * r * std::sin(M_PI / n); }

std::filesystem::path temp_file(const std::string& name, const std::string& text) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() /
                                  ("windplan_cutlines_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p;
}

// The checks every result must pass: planar to 1e-6 of the length, closed/open as asked, no
// longer than the start, on the mesh.
void expect_valid(const Mesh& mesh, const CutLine& c, const CutLineSummary& s, bool closed) {
  SCOPED_TRACE(c.name + ": " + s.brief_report());
  // refine_path may stop early on closed loops; the section polish then gives the result.
  EXPECT_TRUE(s.geodesic.converged() || s.method == "section polish");
  EXPECT_EQ(c.closed, closed);
  ASSERT_GE(c.points.size(), 3u);
  EXPECT_GT(c.length, 0.0);
  EXPECT_LT(c.residual, 1e-6 * c.length);
  EXPECT_NEAR(c.plane_normal.norm(), 1.0, 1e-12);
  double residual = 0.0, len = 0.0;
  for (const Vec3& p : c.points)
    residual = std::max(residual, std::fabs(c.plane_normal.dot(p) - c.plane_offset));
  for (std::size_t i = 1; i < c.points.size(); ++i) len += (c.points[i] - c.points[i - 1]).norm();
  if (closed) len += (c.points.front() - c.points.back()).norm();
  EXPECT_NEAR(residual, c.residual, 1e-12);  // the reported residual is the real one
  EXPECT_NEAR(len, c.length, 1e-9 * len);
  if (closed) {
    EXPECT_LE(c.length, s.initial_length * (1.0 + 1e-12));
  }
  const ClosestPointQuery q(mesh);
  for (const Vec3& p : c.points) EXPECT_LT(q.closest(p).distance, 1e-9);
  EXPECT_TRUE(s.warnings.empty());
}

// ---- plane sections ----

TEST(PlaneSection, PerpendicularPlaneGivesOneRingAroundTheAxis) {
  const auto secs = plane_sections(cylinder(), Vec3::UnitZ(), 55.0, z_axis());
  ASSERT_EQ(secs.size(), 1u);
  EXPECT_TRUE(secs[0].closed);
  EXPECT_EQ(std::abs(secs[0].winding), 1);
  EXPECT_NEAR(secs[0].length, ring_perimeter(kR, kN), 1e-9);
  std::string why;
  EXPECT_TRUE(is_valid_path(cylinder(), secs[0].path, &why)) << why;
  for (const Vec3& p : secs[0].points) EXPECT_NEAR(p.z(), 55.0, 1e-12);
}

TEST(PlaneSection, PlaneThroughTheAxisGivesTwoOpenChainsAndNoLoop) {
  const auto secs = plane_sections(cylinder(), Vec3::UnitX(), 0.3, z_axis());
  ASSERT_EQ(secs.size(), 2u);
  for (const PlaneSection& s : secs) {
    EXPECT_FALSE(s.closed);
    EXPECT_NEAR(s.length, kLen, 1e-9);  // a straight line along the side
  }
  EXPECT_THROW(axial_plane_section(cylinder(), Vec3::UnitX(), 0.3, z_axis(), "t"), InputError);
}

TEST(PlaneSection, ObliquePlaneGivesAnEllipseLongerThanTheRing) {
  const Vec3 n = Vec3(0.4, 0.0, 1.0).normalized();
  const PlaneSection s = axial_plane_section(cylinder(), n, n.dot(Vec3(0, 0, 100)), z_axis(), "t");
  // Ellipse with semi-axes R and R / cos(tilt): longer than the circle.
  EXPECT_GT(s.length, ring_perimeter(kR, kN) * 1.02);
  for (const Vec3& p : s.points) {
    EXPECT_NEAR(n.dot(p), n.dot(Vec3(0, 0, 100)), 1e-9);
    EXPECT_LE(std::hypot(p.x(), p.y()), kR + 1e-9);
  }
}

// ---- closed cut-lines on a cylinder ----

TEST(CutLine, ObliquePlaneOnACylinderConvergesToThePerpendicularRing) {
  CutLineOptions c;
  c.name = "oblique";
  c.has_plane = true;
  c.normal = Vec3(-0.5, 0.2, 1.0);
  c.offset = c.normal.normalized().dot(Vec3(0, 0, 95.0));
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
  expect_valid(cylinder(), r, s, true);
  EXPECT_NEAR(r.length, ring_perimeter(kR, kN), 1e-6 * r.length) << s.brief_report();
  EXPECT_NEAR(std::fabs(r.plane_normal.z()), 1.0, 1e-6);
  EXPECT_GT(s.tilt_deg, 20.0);  // the plane really turned (the start was tilted ~29 deg)
  EXPECT_EQ(s.start, "plane");
}

TEST(CutLine, StationExactlyOnAVertexRingIsAlreadyTheRing) {
  CutLineOptions c;
  c.name = "ring";
  c.has_station = true;
  c.station = kLen * 7 / kM;  // a vertex ring: every crossing at a vertex
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
  expect_valid(cylinder(), r, s, true);
  EXPECT_NEAR(r.length, ring_perimeter(kR, kN), 1e-6 * r.length);
  for (const Vec3& p : r.points) EXPECT_NEAR(p.z(), c.station, 1e-9);  // no reason to move
}

TEST(CutLine, FixedNormalOnlyTranslatesThePlane) {
  CutLineOptions c;
  c.name = "fixed";
  c.has_plane = true;
  c.normal = Vec3(0.3, 0.0, 1.0);
  c.offset = c.normal.normalized().dot(Vec3(0, 0, 100.0));
  c.normal_mode = "fixed";
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
  expect_valid(cylinder(), r, s, true);
  EXPECT_NEAR((r.plane_normal - c.normal.normalized()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.tilt_deg, 0.0, 1e-6);
  // A translated oblique plane gives the same ellipse (prism): the length does not change much.
  EXPECT_NEAR(r.length, s.initial_length, 1e-3 * r.length);
}

TEST(CutLine, ConeModeKeepsTheNormalWithinTheTilt) {
  CutLineOptions c;
  c.name = "cone";
  c.has_plane = true;
  c.normal = Vec3(0.4, 0.0, 1.0);  // 21.8 deg from the axis
  c.offset = c.normal.normalized().dot(Vec3(0, 0, 100.0));
  c.normal_mode = "cone";
  c.max_tilt_deg = 5.0;
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
  expect_valid(cylinder(), r, s, true);
  // The best plane within the cone is tilted by the full 5 degrees towards the axis.
  EXPECT_NEAR(s.tilt_deg, 5.0, 1e-3);
  const double from_axis = std::acos(std::fabs(r.plane_normal.z())) * 180.0 / M_PI;
  EXPECT_NEAR(from_axis, std::atan(0.4) * 180.0 / M_PI - 5.0, 1e-2);
  EXPECT_GT(r.length, ring_perimeter(kR, kN) * (1.0 + 1e-4));
}

TEST(CutLine, ClosedCsvCurveConvergesToTheRing) {
  std::string csv = "x,y,z\n# an oblique, slightly wavy ring around the cylinder\n";
  for (int i = 0; i < 40; ++i) {
    const double t = 2.0 * M_PI * i / 40;
    const double r = kR + 0.5 * std::sin(3 * t);
    csv += std::to_string(r * std::cos(t)) + "," + std::to_string(r * std::sin(t)) + "," +
           std::to_string(100.0 + 15.0 * std::cos(t)) + "\n";
  }
  CutLineOptions c;
  c.name = "csv";
  c.init = temp_file("ring.csv", csv);
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
  std::filesystem::remove(c.init);
  expect_valid(cylinder(), r, s, true);
  EXPECT_NEAR(r.length, ring_perimeter(kR, kN), 1e-6 * r.length) << s.brief_report();
  EXPECT_NEAR(std::fabs(r.plane_normal.z()), 1.0, 1e-6);
}

// ---- open coplanar curves ----

TEST(CutLine, OpenCurveOnARingIsTheRingArc) {
  CutLineOptions c;
  c.name = "arc";
  c.closed = false;
  const double z = kLen * 10 / kM;  // vertex ring
  c.from = Vec3(kR, 0.0, z);
  c.to = Vec3(0.0, kR, z);  // a vertex (kN divisible by 4)
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
  expect_valid(cylinder(), r, s, false);
  EXPECT_NEAR(r.length, ring_perimeter(kR, kN) / 4.0, 1e-6 * r.length);
  EXPECT_NEAR((r.points.front() - c.from).norm(), 0.0, 1e-9);
  EXPECT_NEAR((r.points.back() - c.to).norm(), 0.0, 1e-9);
}

TEST(CutLine, OpenCurveAcrossAHelixIsPlanarThroughBothPointsAndNotShorterThanTheGeodesic) {
  CutLineOptions c;
  c.name = "helix";
  c.closed = false;
  c.from = Vec3(kR, 0.0, 40.0);
  c.to = Vec3(-kR * std::cos(0.3), kR * std::sin(0.3), 140.0);
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
  expect_valid(cylinder(), r, s, false);
  const ClosestPointQuery q(cylinder());
  const Vec3 a = q.closest(c.from).position, b = q.closest(c.to).position;
  EXPECT_LT(std::fabs(r.plane_normal.dot(a) - r.plane_offset), 1e-6 * r.length);
  EXPECT_LT(std::fabs(r.plane_normal.dot(b) - r.plane_offset), 1e-6 * r.length);
  // The geodesic (the start) is the shortest curve: the planar one is no shorter, and the
  // straight chord bounds both from below.
  EXPECT_GE(r.length, (b - a).norm());
  EXPECT_LE(r.length, s.initial_length * 1.5);
  // Locally shortest: turning the plane about the line a-b by +-1 degree lengthens the arc.
  const Vec3 u = (b - a).normalized();
  for (double deg : {-1.0, 1.0}) {
    const Vec3 n = Eigen::AngleAxisd(deg * M_PI / 180.0, u) * r.plane_normal;
    const std::vector<Vec3> arc = section_arc(cylinder(), n, n.dot(a), a, b, 1e-6);
    ASSERT_FALSE(arc.empty());
    double len = 0.0;
    for (std::size_t i = 1; i < arc.size(); ++i) len += (arc[i] - arc[i - 1]).norm();
    EXPECT_GT(len, r.length) << deg << " deg";
  }
}

// A station cut-line stays at its station: on a cylinder every perpendicular loop is equally
// short, and a free offset drifted (the vessel's station 150 came out at 165.2 mm). By default
// the plane is the station's own; with a free normal it only turns about the start loop's
// centre (keep_offset), which on a cylinder leaves it where it is.
TEST(CutLine, StationStaysAtItsStation) {
  for (const char* mode : {"", "free", "cone"}) {
    CutLineOptions c;
    c.name = "split";
    c.has_station = true;
    c.station = 37.0;
    c.normal_mode = mode;
    CutLineSummary s;
    const CutLine r = compute_cutline(cylinder(), c, z_axis(), {}, &s);
    SCOPED_TRACE(mode);
    expect_valid(cylinder(), r, s, true);
    for (const Vec3& p : r.points) EXPECT_NEAR(p.z(), 37.0, 1e-9);
    EXPECT_NEAR(r.plane_offset, 37.0, 1e-9);
    EXPECT_NEAR(r.plane_normal.z(), 1.0, 1e-12);
    EXPECT_NEAR(r.length, ring_perimeter(kR, kN), 1e-9);
  }
  // A tilted start plane with a free normal turns about its loop's centre (z = 37).
  CutLineOptions t;
  t.name = "tilted";
  t.has_plane = true;
  t.normal = Vec3(0.2, 0.0, 1.0).normalized();
  t.offset = 37.0;
  CutLineSummary s;
  const CutLine r = compute_cutline(cylinder(), t, z_axis(), {}, &s);
  expect_valid(cylinder(), r, s, true);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : r.points) centre += p / static_cast<double>(r.points.size());
  EXPECT_NEAR(centre.z(), 37.0, 1.0);  // the pivot is the mean of the crossings: near the centre
  EXPECT_LT(r.length, s.initial_length);
}

// ---- the bend of a bent tube (the shipped job) ----

TEST(CutLine, ObliqueStartInABendGivesTheCircularCrossSection) {
  const Job job = load_job(test::source_dir() / "configs" / "bent_tube.yaml");
  const Mandrel m = build_mandrel(job);
  const BentTubeParams& bt = job.mandrel.bent_tube;
  ASSERT_EQ(bt.bends.size(), 1u);
  const double R = bt.radius, bend = bt.bends[0].radius, seg = bt.segments[0];
  // The first leg runs along +z from the origin, the bend turns towards +x about the y axis
  // through (bend, 0, seg); its middle cross-section has the normal (1, 0, 1)/sqrt(2).
  const Vec3 centre(bend, 0.0, seg);
  const Vec3 mid = centre + Vec3(-bend * std::cos(M_PI / 4), 0.0, bend * std::sin(M_PI / 4));
  const Vec3 tangent = Vec3(1.0, 0.0, 1.0).normalized();
  const Vec3 w = tangent.cross(Vec3::UnitY());
  CutLineOptions c;
  c.name = "bend";
  c.has_plane = true;
  c.normal = (Eigen::AngleAxisd(12.0 * M_PI / 180.0, w) *
              Eigen::AngleAxisd(-8.0 * M_PI / 180.0, Vec3::UnitY()) * tangent);
  c.offset = c.normal.normalized().dot(mid);
  std::vector<CutLineSummary> sums;
  const std::vector<CutLine> rs = compute_cutlines(m.winding.mesh, m.axis, {c}, {}, &sums);
  ASSERT_EQ(rs.size(), 1u);
  const CutLine& r = rs[0];
  expect_valid(m.winding.mesh, r, sums[0], true);
  // The tessellation's points lie on the tube; the section's points on chords of it, at most the
  // linear deflection inside.
  const double delta = job.mandrel.tessellation.linear_deflection;
  EXPECT_LE(r.length, 2.0 * M_PI * R * (1.0 + 1e-9)) << sums[0].brief_report();
  EXPECT_GE(r.length, 2.0 * M_PI * (R - delta)) << sums[0].brief_report();
  // A circular cross-section of the tube: the loop's centre lies on the centreline, the plane's
  // normal is the centreline's tangent there, every point is ~R from the centre. (Cross-sections
  // all have the same length, so the loop may settle anywhere near the start: report where.)
  Vec3 ctr = Vec3::Zero();
  for (const Vec3& p : r.points) ctr += p;
  ctr /= static_cast<double>(r.points.size());
  const std::vector<Vec3> line = bent_tube_centreline(bt, 720);
  double dist = 1e300;
  Vec3 tangent_there = Vec3::UnitZ(), foot = Vec3::Zero();
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Vec3 e = line[i] - line[i - 1];
    const double t = std::clamp((ctr - line[i - 1]).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const double dd = (line[i - 1] + t * e - ctr).norm();
    if (dd < dist) dist = dd, tangent_there = e.normalized(), foot = line[i - 1] + t * e;
  }
  EXPECT_LT(dist, 2.0 * delta) << "loop centre " << ctr.transpose();
  // Within a few degrees (the bend is tessellated at 10 degrees of arc, so the mesh's shortest
  // planar loop need not be exactly normal to the smooth centreline) ...
  EXPECT_GT(std::fabs(r.plane_normal.dot(tangent_there)), std::cos(3.0 * M_PI / 180.0))
      << "normal " << r.plane_normal.transpose() << ", tangent " << tangent_there.transpose();
  // ... and no longer than the mesh's section by the exact cross-section plane there.
  const PlaneSection exact =
      axial_plane_section(m.winding.mesh, tangent_there, tangent_there.dot(foot), m.axis, "exact");
  EXPECT_LE(r.length, exact.length + 1e-9);
  EXPECT_NEAR(r.plane_normal.y(), 0.0, 1e-3);
  for (const Vec3& p : r.points) {
    EXPECT_LE((p - ctr).norm(), R + 2.0 * delta);
    EXPECT_GE((p - ctr).norm(), R - 2.0 * delta);
  }
  // The start was in the bend, 45 degrees round it; the result stays near it.
  EXPECT_LT((ctr - mid).norm(), 0.5 * bend) << "loop centre " << ctr.transpose();
}

// ---- the job section and bad input ----

TEST(CutLineJob, DecodesTheSection) {
  const Job job = load_job_from_string(
      "mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 200}\n"
      "cutlines:\n"
      "  - {name: a, plane: {normal: [0, 0.2, 1], offset: 40}, normal_mode: cone, max_tilt_deg: "
      "10}\n"
      "  - {station: 150, normal_mode: fixed}\n"
      "  - {name: c, init: curves/c.csv}\n"
      "  - {name: d, closed: false, from: [50, 0, 10], to: [0, 50, 90]}\n",
      "/jobs/t.yaml");
  ASSERT_EQ(job.cutlines.size(), 4u);
  EXPECT_EQ(job.cutlines[0].name, "a");
  EXPECT_TRUE(job.cutlines[0].has_plane);
  EXPECT_EQ(job.cutlines[0].normal, Vec3(0, 0.2, 1));
  EXPECT_EQ(job.cutlines[0].normal_mode, "cone");
  EXPECT_EQ(job.cutlines[0].max_tilt_deg, 10.0);
  EXPECT_EQ(job.cutlines[1].name, "cut2");
  EXPECT_TRUE(job.cutlines[1].has_station);
  EXPECT_EQ(job.cutlines[1].station, 150.0);
  EXPECT_EQ(job.cutlines[2].init, std::filesystem::path("/jobs/curves/c.csv"));
  EXPECT_FALSE(job.cutlines[3].closed);
  EXPECT_EQ(job.cutlines[3].to, Vec3(0, 50, 90));
}

void expect_config_error(const std::string& section, const std::string& needle) {
  try {
    load_job_from_string("mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 200}\n" + section,
                         "/jobs/bad.yaml");
    ADD_FAILURE() << "expected ConfigError for: " << section;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/jobs/bad.yaml"), std::string::npos) << e.what();
  }
}

TEST(CutLineJob, RejectsBadSections) {
  expect_config_error("cutlines:\n  - {name: a, station: 10, speed: 3}\n",
                      "bad.yaml:5: unknown key 'cutlines[0].speed'");
  expect_config_error("cutlines:\n  - {name: a, plane: {normal: [0, 0, 1], offset: 1, d: 2}}\n",
                      "unknown key 'cutlines[0].plane.d'");
  expect_config_error("cutlines:\n  - {name: a, plane: {normal: [0, 0, 0], offset: 1}}\n",
                      "non-zero");
  expect_config_error(
      "cutlines:\n  - {name: a, station: 10, plane: {normal: [0, 0, 1], offset: 1}}\n",
      "exactly one of plane, station, init");
  expect_config_error("cutlines:\n  - {name: a}\n", "exactly one of plane, station, init");
  expect_config_error("cutlines:\n  - {name: a, station: 1, normal_mode: tilt}\n", "normal_mode");
  expect_config_error("cutlines:\n  - {name: a, station: 1, max_tilt_deg: 0}\n", "max_tilt_deg");
  expect_config_error("cutlines:\n  - {name: a, closed: false, from: [1, 0, 0]}\n", "to");
  expect_config_error("cutlines:\n  - {name: a, station: 1, from: [1, 0, 0]}\n", "from");
  expect_config_error("cutlines: {name: a}\n", "expected a list");
}

TEST(CutLineBadInput, PlaneThatMissesTheMandrel) {
  CutLineOptions c;
  c.name = "far";
  c.has_station = true;
  c.station = kLen + 10.0;
  try {
    compute_cutline(cylinder(), c, z_axis());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cut-line 'far'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("misses the mandrel"), std::string::npos) << e.what();
  }
}

TEST(CutLineBadInput, PlaneThatDoesNotGoAroundTheAxis) {
  CutLineOptions c;
  c.name = "steep";
  c.has_plane = true;
  c.normal = Vec3(1.0, 0.0, 0.05);  // nearly through the axis: cuts the side twice, open chains
  c.offset = 10.0;
  EXPECT_THROW(compute_cutline(cylinder(), c, z_axis()), InputError);
}

TEST(CutLineBadInput, CurveThatIsNotClosed) {
  std::string csv;
  for (int i = 0; i <= 20; ++i) {  // half a ring
    const double t = M_PI * i / 20;
    csv += std::to_string(kR * std::cos(t)) + "," + std::to_string(kR * std::sin(t)) + ",100\n";
  }
  CutLineOptions c;
  c.name = "half";
  c.init = temp_file("half.csv", csv);
  try {
    compute_cutline(cylinder(), c, z_axis());
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not closed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cut-line 'half'"), std::string::npos) << e.what();
  }
  std::filesystem::remove(c.init);
}

TEST(CutLineBadInput, BadCsvAndMissingFile) {
  CutLineOptions c;
  c.name = "bad";
  c.init = temp_file("bad.csv", "x,y,z\n1,2,3\n4,five,6\n");
  try {
    compute_cutline(cylinder(), c, z_axis());
    ADD_FAILURE() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:3"), std::string::npos) << e.what();
  }
  std::filesystem::remove(c.init);
  c.init = "/nonexistent/curve.csv";
  EXPECT_THROW(compute_cutline(cylinder(), c, z_axis()), IoError);
}

TEST(CutLineBadInput, ZeroNormalAndOpenCurveFarFromTheSurface) {
  CutLineOptions c;
  c.name = "zero";
  c.has_plane = true;
  c.normal = Vec3::Zero();
  std::string why;
  EXPECT_FALSE(c.is_valid(&why));
  EXPECT_NE(why.find("non-zero"), std::string::npos);
  EXPECT_THROW(compute_cutline(cylinder(), c, z_axis()), ConfigError);
  CutLineOptions o;
  o.name = "far";
  o.closed = false;
  o.from = Vec3(kR, 0, 10);
  o.to = Vec3(500, 0, 10);
  try {
    compute_cutline(cylinder(), o, z_axis());
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("to (500"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace windplan
