#include "planner/plan_layup.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/mesh/closest_point.h"
#include "planner/job/job.h"

namespace windplan {
namespace {

constexpr double kR = 50.0;

Job pipe_job(const std::string& layers) {
  return load_job_from_string(
      "mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 300}\n"
      "material: {tex: 800, fibre_density: 1.8, fibre_volume_fraction: 0.6, tows: 2}\n"
      "winding: {turns: 2, circuits: auto, band_width: 10}\n" +
          layers,
      "/jobs/pipe_layup.yaml");
}

TEST(Layup, HoopOnHoopHasTheAngleOfRadiusRPlusT) {
  const LayupResult r =
      plan_layup(pipe_job("layers:\n  - kind: hoop\n  - kind: hoop\n    overlap: 2\n"));
  ASSERT_TRUE(r.revolution);
  ASSERT_EQ(r.plan.layers.size(), 2u);
  const LayerSummary &a = r.plan.layers[0], &b = r.plan.layers[1];
  // Band: 2 tows of 800 / 1800 mm^2 in 10 mm at V_f 0.6.
  const double t = 2.0 * (800.0 / 1800.0) / (10.0 * 0.6);
  EXPECT_NEAR(a.band_thickness, t, 1e-12);
  // Hoop thickness 2 B t / (p sin a) with p = B on radius R; the tessellated pipe's meridian is
  // the polygon's largest radius, R to 1e-9.
  const double sin_a = std::sin(std::atan(2.0 * M_PI * kR / 10.0));
  EXPECT_NEAR(a.surface_radius, kR, 1e-6);
  EXPECT_NEAR(a.thickness_cylinder, 2.0 * 10.0 * t / (10.0 * sin_a), 1e-9);
  // Angles are measured on the path over a band-width window (planner/winding/fibre_metrics.h): the
  // chord of a helix is short of its tangent's hoop part by sin(d) / d, d = (B/2) / R: on R = 50,
  // 0.003 deg at 88.2 deg.
  constexpr double kWindow = 5e-3;
  EXPECT_NEAR(a.angle, std::atan(2.0 * M_PI * kR / 10.0) * 180.0 / M_PI, kWindow);
  // The second layer is wound on R + t1 with pitch 8.
  const double R2 = kR + a.thickness_cylinder;
  EXPECT_NEAR(b.surface_radius, R2, 1e-6);
  EXPECT_NEAR(b.angle, std::atan(2.0 * M_PI * R2 / 8.0) * 180.0 / M_PI, kWindow);
  EXPECT_DOUBLE_EQ(b.pitch, 8.0);
  // Its points lie on radius R + t1 (on the cylinder's middle).
  for (const FibrePoint& p : r.layers[1].circuits[0].points) {
    const double z = p.position.z();
    if (z > 50.0 && z < 250.0) {
      ASSERT_NEAR(std::hypot(p.position.x(), p.position.y()), R2, 1e-6);
    }
  }
  // The plan holds both layers' circuits in order, renumbered.
  ASSERT_EQ(r.plan.circuits.size(), 2u);
  EXPECT_EQ(r.plan.circuits[1].index, 1);
  EXPECT_EQ(b.first_circuit, 1);
  // The outer profile is R + t1 + t2 on the cylinder.
  EXPECT_NEAR(r.plan.profile.at(150.0), R2 + b.thickness_cylinder, 1e-6);
  // Material: fibre mass of the band length.
  const double mass = 1e-3 * 1.8 * 0.6 * 10.0 * t * a.band_length;
  EXPECT_NEAR(a.fibre_mass, mass, 1e-9 * mass);
  EXPECT_NEAR(r.total.fibre_mass, a.fibre_mass + b.fibre_mass, 1e-9);
}

// PipelineOptions::on_layer_surface: called once before each layer wound over others, naming it,
// with the surface it is then wound on (the robot cell's reach is checked there, before the layer
// is planned): the second hoop's surface is R + t1 on the cylinder, the third's R + t1 + t2.
TEST(Layup, EachLayerOverOthersShowsItsSurfaceBeforeItIsPlanned) {
  std::vector<std::string> names;
  std::vector<double> radii;
  PipelineOptions po;
  po.on_layer_surface = [&](const Mesh& surface, const std::string& layer) {
    names.push_back(layer);
    double r = 0.0;  // the largest radius of its vertices at mid-length
    for (const Vec3& p : surface.points()) {
      if (std::fabs(p.z() - 150.0) < 20.0) r = std::max(r, std::hypot(p.x(), p.y()));
    }
    radii.push_back(r);
  };
  const LayupResult r =
      plan_layup(pipe_job("layers:\n  - {kind: hoop, name: a}\n  - {kind: hoop, name: b}\n"
                          "  - {kind: hoop, name: c}\n"),
                 po);
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[0], "layers[1] (b)");
  EXPECT_EQ(names[1], "layers[2] (c)");
  const double t1 = r.plan.layers[0].thickness_cylinder, t2 = r.plan.layers[1].thickness_cylinder;
  EXPECT_NEAR(radii[0], kR + t1, 1e-6);
  EXPECT_NEAR(radii[1], kR + t1 + t2, 1e-6);
  // A refusal there stops the layup before the layer is planned.
  po.on_layer_surface = [](const Mesh&, const std::string& layer) {
    throw InputError(layer + ": refused");
  };
  EXPECT_THROW(plan_layup(pipe_job("layers:\n  - kind: hoop\n  - kind: hoop\n"), po), InputError);
}

TEST(Layup, HelicalCylinderThicknessFromItsOwnCircuits) {
  const LayupResult r = plan_layup(pipe_job("layers:\n  - kind: helical\n  - kind: hoop\n"));
  const LayerSummary &h = r.plan.layers[0], &o = r.plan.layers[1];
  EXPECT_EQ(h.kind, "helical");
  // 2 K B t / (2 pi R cos alpha), K its circuits, alpha = asin(c / R) its measured constant.
  const double cos_a = std::sqrt(1.0 - h.clairaut * h.clairaut / (kR * kR));
  const double expect = 2.0 * h.circuits * 10.0 * h.band_thickness / (2.0 * M_PI * kR * cos_a);
  EXPECT_NEAR(h.thickness_cylinder, expect, 1e-6 * expect);
  EXPECT_NEAR(std::asin(h.clairaut / kR) * 180.0 / M_PI, h.angle, 0.5);
  // auto circuits cover the cylinder: about 2 t.
  EXPECT_GE(h.thickness_cylinder, 2.0 * h.band_thickness * 0.999);
  EXPECT_LT(h.thickness_cylinder, 2.0 * h.band_thickness * 1.3);
  // The hoop on top: the angle of radius R + t_helical.
  const double R2 = kR + h.thickness_cylinder;
  EXPECT_NEAR(o.angle, std::atan(2.0 * M_PI * R2 / 10.0) * 180.0 / M_PI, 5e-3);  // as above
  // Per-face thickness for the FEA export: the layer's cylinder thickness mid-pipe.
  const Mesh& m = r.mandrel.winding.mesh;
  for (int f = 0; f < m.num_faces(); ++f) {
    const double z = m.face_centroid(f).z();
    if (z > 100.0 && z < 200.0) {
      ASSERT_NEAR(r.layers[0].face_thickness[f], h.thickness_cylinder, 1e-6) << f;
    }
  }
}

TEST(Layup, AJobWithoutLayersIsOneHelicalLayer) {
  const LayupResult r = plan_layup(pipe_job(""));
  ASSERT_EQ(r.plan.layers.size(), 1u);
  EXPECT_EQ(r.plan.layers[0].name, "helical1");
  EXPECT_EQ(r.plan.metrics.circuits, static_cast<int>(r.plan.circuits.size()));
}

TEST(Layup, HoopRangeOutsideTheMandrelNamesTheLayer) {
  try {
    plan_layup(pipe_job("layers:\n  - kind: helical\n  - kind: hoop\n    range: [100, 400]\n"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("layers[1].range"), std::string::npos) << e.what();
  }
}

TEST(Layup, RevolvedMeridianIsAnAnnulusOnTheMeridian) {
  const MeridianPolyline m =
      MeridianPolyline::from_points({Vec2(0, 20), Vec2(50, 30), Vec2(100, 30)});
  const Mesh mesh = revolve_meridian(m, SpindleAxis{}, 5.0);
  const WindingSurface ws =
      extract_winding_surface(mesh, std::vector<char>(mesh.num_faces(), 1), SpindleAxis{});
  EXPECT_NEAR(ws.loops[0].mean_radius, 20.0, 1e-9);
  EXPECT_NEAR(ws.loops[1].mean_radius, 30.0, 1e-9);
  for (const Vec3& p : mesh.points()) {
    const double r = std::hypot(p.x(), p.y());
    EXPECT_NEAR(r, p.z() < 50.0 ? 20.0 + p.z() / 5.0 : 30.0, 1e-9);
  }
  // Outward normals.
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 c = mesh.face_centroid(f);
    EXPECT_GT(mesh.face_normal(f).dot(Vec3(c.x(), c.y(), 0.0)), 0.0);
  }
}

// A pipe's laminate: 52.4 mm on the cylinder, tapering to 51.1 mm over the last 15 mm at each
// end, revolved with the long edge of a pipe mesh (its triangles run end to end: 200 mm). The
// rings stay as close along the meridian as around it (2 pi 52.4 / 48 = 6.9 mm), so every point
// of the meridian lies on the mesh within the 48-gon's sag (0.11 mm) plus a ring chord across
// the taper's knee (1.3 / 15 x 6.9 / 4 = 0.15 mm); with rings 200 mm apart the surface was a
// double cone, 1.2 mm under the laminate at the ends.
TEST(Layup, RevolvedMeridianKeepsItsTaperWithLongMeshEdges) {
  std::vector<Vec2> pts;
  for (int i = 0; i <= 600; ++i) {
    const double x = 0.5 * i, e = std::min(x, 300.0 - x);
    pts.emplace_back(x, e < 15.0 ? 51.1 + 1.3 * e / 15.0 : 52.4);
  }
  const MeridianPolyline m = MeridianPolyline::from_points(pts);
  const Mesh mesh = revolve_meridian(m, SpindleAxis{}, 200.0);
  const ClosestPointQuery q(mesh);
  double worst = 0.0;
  for (const Vec2& p : pts) {
    for (double t : {0.0, 0.7, 2.1}) {
      worst = std::max(worst,
                       q.closest(Vec3(p.y() * std::cos(t), p.y() * std::sin(t), p.x())).distance);
    }
  }
  EXPECT_LT(worst, 52.4 * (1 - std::cos(M_PI / 48)) + 1.3 / 15 * 6.9 / 4);
  // A fine edge keeps its rings `edge` apart as before (vessel_layup's meshes): 2 mm on the
  // 300 mm meridian, ceil(2 pi 52.4 / 2) = 165 around.
  const Mesh fine = revolve_meridian(m, SpindleAxis{}, 2.0);
  EXPECT_EQ(fine.num_vertices() % 165, 0);
  EXPECT_NEAR(fine.num_vertices() / 165, 151, 1);
}

Job bent_tube_job(const std::string& layers) {
  return load_job_from_string(
      "mandrel:\n  source: bent_tube\n"
      "  bent_tube: {radius: 25, segments: [200, 200], bends: [{angle: 90, radius: 100}]}\n"
      "material: {tows: 2}\nwinding: {turns: 6, circuits: 4, band_width: 8}\n"
      "girth: {samples: 8}\n" +
          layers,
      "/jobs/bent_layup.yaml");
}

TEST(Layup, OffRevolutionTheMeshIsMovedByTheMeasuredThickness) {
  const LayupResult r =
      plan_layup(bent_tube_job("layers:\n  - kind: helical\n  - kind: helical\n"));
  ASSERT_FALSE(r.revolution);
  ASSERT_EQ(r.layers.size(), 2u);
  const Mesh& m = r.mandrel.winding.mesh;
  for (const LayupLayer& L : r.layers) {
    // The band volume t B L is spread over the faces: it is all there.
    double volume = 0.0;
    for (int f = 0; f < m.num_faces(); ++f) volume += L.face_thickness[f] * m.face_area(f);
    const double expect = L.summary.band_thickness * L.summary.band_width * L.summary.band_length;
    EXPECT_NEAR(volume, expect, 0.02 * expect) << L.summary.name;
    EXPECT_TRUE(std::isnan(L.summary.thickness_cylinder));
    EXPECT_GT(L.summary.thickness_max, 0.0);
  }
  // The second layer lies outside the mandrel: its points are farther from the tube's
  // centreline than the radius, by about the first layer's thickness there.
  const ClosestPointQuery q(m);
  double above = 0.0;
  int n = 0;
  for (const Circuit& c : r.layers[1].circuits) {
    for (const FibrePoint& p : c.points) {
      above += q.closest(p.position).distance;
      ++n;
    }
  }
  double volume = 0.0;
  for (int f = 0; f < m.num_faces(); ++f) volume += r.layers[0].face_thickness[f] * m.face_area(f);
  const double mean = volume / m.total_area();
  EXPECT_GT(above / n, 0.5 * mean);
  EXPECT_LT(above / n, 2.0 * mean);
}

TEST(Layup, HoopOffRevolutionIsRejected) {
  try {
    plan_layup(bent_tube_job("layers:\n  - kind: helical\n  - kind: hoop\n"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("layers[1]: a hoop layer needs"), std::string::npos)
        << e.what();
  }
}

// design: on the shipped vessel's mandrel: the stagger moves the second helical layer's
// turnaround one band outward (the pattern may move each by a quarter band), the spline model
// keeps the layer finite at it, and the netting burst is the closed form of the measured layers.
TEST(Layup, DesignStaggerSplineAndNettingBurst) {
  const Job job = load_job_from_string(
      "mandrel:\n  source: vessel\n  remesh: 6\n  vessel: {radius: 100, length: 300, dome: "
      "{type: isotensoid, polar_opening: 30}}\n"
      "material: {tows: 4}\nwinding: {pattern: auto, band_width: 16, beta: 0, mu: 0.2}\n"
      "layers:\n  - kind: helical\n  - kind: helical\n"
      "design: {pressure: 5, fibre_strength: 4900, dome_thickness: spline, "
      "turnaround_stagger: 1}\n",
      "/jobs/vessel_design.yaml");
  EXPECT_FALSE(job.sized);
  const LayupResult r = plan_layup(job);
  ASSERT_EQ(r.plan.layers.size(), 2u);
  const double c1 = r.plan.layers[0].clairaut, c2 = r.plan.layers[1].clairaut;
  EXPECT_GE(c2 - c1, 0.75 * 16.0) << c1 << " " << c2;
  EXPECT_LE(c2 - c1, 1.25 * 16.0) << c1 << " " << c2;
  for (const LayerThickness& t : r.profiles.thickness) EXPECT_TRUE(std::isfinite(t.max()));
  ASSERT_EQ(r.profiles.alternative.size(), 2u);
  ASSERT_TRUE(r.has_netting);
  EXPECT_NEAR(r.netting_radius, 100.0, 0.05);  // the mandrel's largest radius, tessellated
  double ax = 0.0, hp = 0.0;
  for (const LayerSummary& L : r.plan.layers) {
    const double a = L.angle * M_PI / 180.0;
    ax += 2.0 * 4900.0 * 0.6 * L.thickness_cylinder * std::cos(a) * std::cos(a) / r.netting_radius;
    hp += 4900.0 * 0.6 * L.thickness_cylinder * std::sin(a) * std::sin(a) / r.netting_radius;
  }
  EXPECT_NEAR(r.netting.pressure, std::min(ax, hp), 1e-9 * ax);
}

}  // namespace
}  // namespace windplan
