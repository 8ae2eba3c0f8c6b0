#include "export/files/laminate_fea.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "planner/layup/hoop.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

constexpr double kR = 50.0, kLength = 200.0, kAlpha = 35.0;

// Helices of angle +alpha (x and phi increasing) or -alpha (x decreasing, phi increasing) on the
// cylinder of radius r about z, one per start angle, points every 2 mm of arc.
std::vector<Circuit> helices(double r, double alpha_deg, int count, bool plus) {
  std::vector<Circuit> out;
  const double a = alpha_deg * M_PI / 180.0, len = kLength / std::cos(a);
  for (int k = 0; k < count; ++k) {
    Circuit c;
    c.index = k;
    for (double s = 0.0; s <= len; s += 2.0) {
      const double x = plus ? s * std::cos(a) : kLength - s * std::cos(a);
      const double phi = 2.0 * M_PI * k / count + s * std::sin(a) / r;
      FibrePoint p;
      p.position = Vec3(r * std::cos(phi), r * std::sin(phi), x);
      c.points.push_back(p);
    }
    out.push_back(std::move(c));
  }
  return out;
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("windplan_laminate_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::vector<LaminateLayerFaces> cylinder_laminate(const Mesh& mesh) {
  const SpindleAxis axis;
  LaminateLayerFaces helical;
  helical.name = "helical 35";
  helical.kind = "helical";
  std::vector<Circuit> paths = helices(kR, kAlpha, 12, true);
  for (Circuit& c : helices(kR, kAlpha, 12, false)) paths.push_back(std::move(c));
  helical.angles = measure_face_angles(mesh, axis, paths);
  helical.thickness.assign(mesh.num_faces(), 0.5);
  // A hoop layer wound on the helical one (radius R + 0.5): found on the faces below it.
  LaminateLayerFaces hoop;
  hoop.name = "hoop";
  hoop.kind = "hoop";
  RadiusProfile outer;
  outer.axial = {0.0, kLength};
  outer.radius = {kR + 0.5, kR + 0.5};
  HoopOptions ho;
  ho.x0 = 20.0;
  ho.x1 = 180.0;
  const HoopLayer L = plan_hoop_layer(outer, axis, ho);
  hoop.angles = measure_face_angles(mesh, axis, L.circuits);
  hoop.thickness.assign(mesh.num_faces(), 0.0);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double z = mesh.face_centroid(f).z();
    if (z > 20.0 && z < 180.0) hoop.thickness[f] = 0.4;
  }
  return {helical, hoop};
}

TEST(LaminateFea, AnglesMeasuredFromThePathsOnACylinder) {
  const Mesh mesh(test::open_cylinder(kR, kLength, 64, 40));
  const std::vector<LaminateLayerFaces> layers = cylinder_laminate(mesh);
  const FaceFibreAngles& h = layers[0].angles;
  int plus = 0, minus = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (h.length_plus[f] > 1.0) {
      EXPECT_NEAR(h.angle_plus[f], kAlpha, 0.1) << f;
      ++plus;
    }
    if (h.length_minus[f] > 1.0) {
      EXPECT_NEAR(h.angle_minus[f], -kAlpha, 0.1) << f;
      ++minus;
    }
  }
  EXPECT_GT(plus, mesh.num_faces() / 8);
  EXPECT_GT(minus, mesh.num_faces() / 8);
  // The hoop layer: +-atan(2 pi (R + 0.5) / p) on the faces of its range, away from the ends.
  const double hoop = std::atan(2.0 * M_PI * (kR + 0.5) / 10.0) * 180.0 / M_PI;
  const FaceFibreAngles& o = layers[1].angles;
  int hoop_faces = 0, inside = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double z = mesh.face_centroid(f).z();
    if (z < 40.0 || z > 160.0) {
      if (z < 10.0 || z > 190.0) {
        EXPECT_EQ(o.length_plus[f] + o.length_minus[f], 0.0) << f;
      }
      continue;
    }
    ++inside;
    if (o.length_plus[f] > 1.0) {
      EXPECT_NEAR(o.angle_plus[f], hoop, 0.05) << f;
    }
    if (o.length_minus[f] > 1.0) {
      EXPECT_NEAR(o.angle_minus[f], -hoop, 0.05) << f;
    }
    if (o.length_plus[f] + o.length_minus[f] > 1.0) ++hoop_faces;
  }
  EXPECT_GT(hoop_faces, inside / 2);
  // The length measured is the paths' length.
  double total = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f) total += h.length_plus[f] + h.length_minus[f];
  const double path = 24.0 * kLength / std::cos(kAlpha * M_PI / 180.0);
  EXPECT_NEAR(total, path, 2.0 * 24.0);  // the last step of each helix is short of its end
}

TEST(LaminateFea, CsvHasARowPerFaceAndLayer) {
  const Mesh mesh(test::open_cylinder(kR, kLength, 32, 10));
  const std::vector<LaminateLayerFaces> layers = cylinder_laminate(mesh);
  const CsvTable t = laminate_table(mesh, layers);
  ASSERT_EQ(t.rows.size(), 2u * mesh.num_faces());
  EXPECT_EQ(t.header[2], "thickness [mm]");
  EXPECT_EQ(t.rows[0][1], 0.0);
  EXPECT_EQ(t.rows[1][1], 1.0);
  EXPECT_EQ(t.rows[0][2], 0.5);
  std::vector<LaminateLayerFaces> bad = layers;
  bad[1].thickness.pop_back();
  EXPECT_THROW(laminate_table(mesh, bad), InputError);
}

// Runs tests/export/read_vtu.py with a Python that has VTK (Debian's python3-vtk9 is for the
// system interpreter, which a pyenv python3 on PATH would hide); 77: no VTK anywhere.
int read_with_vtk(const fs::path& vtu, const fs::path& out) {
  const std::string script = std::string(WINDPLAN_SOURCE_DIR) + "/tests/export/read_vtu.py";
  int rc = 77;
  for (const char* py : {"/usr/bin/python3", "python3"}) {
    const std::string cmd =
        std::string(py) + " '" + script + "' '" + vtu.string() + "' > '" + out.string() + "' 2>&1";
    const int status = std::system(cmd.c_str());
    rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (rc != 77 && rc != 127) return rc;
  }
  return rc;
}

TEST(LaminateFea, VtuReadBackByVtk) {
  const Mesh mesh(test::open_cylinder(kR, kLength, 48, 20));
  const std::vector<LaminateLayerFaces> layers = cylinder_laminate(mesh);
  TempDir dir;
  const std::vector<std::string> files = write_laminate_fea(dir.path, mesh, SpindleAxis{}, layers);
  ASSERT_EQ(files.size(), 2u);
  const fs::path out = dir.path / "vtk.txt";
  const int rc = read_with_vtk(dir.path / "laminate.vtu", out);
  const std::string text = read_text_file(out);
  if (rc == 77 || rc == 127) GTEST_SKIP() << "VTK's Python bindings are missing: " << text;
  ASSERT_EQ(rc, 0) << text;

  std::map<std::string, std::vector<double>> arrays;
  std::map<std::string, int> components;
  long points = -1, cells = -1;
  std::vector<int> types;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string what;
    ls >> what;
    if (what == "points") ls >> points;
    if (what == "cells") ls >> cells;
    if (what == "types") {
      for (int t; ls >> t;) types.push_back(t);
    }
    if (what == "array") {
      std::string name;
      int comp = 0, tuples = 0;
      ls >> name >> comp >> tuples;
      components[name] = comp;
      for (double v; ls >> v;) arrays[name].push_back(v);
      EXPECT_EQ(static_cast<int>(arrays[name].size()), comp * tuples) << name;
    }
  }
  EXPECT_EQ(points, mesh.num_vertices());
  EXPECT_EQ(cells, mesh.num_faces());
  ASSERT_EQ(static_cast<int>(types.size()), mesh.num_faces());
  for (int t : types) EXPECT_EQ(t, 5);  // VTK_TRIANGLE
  for (const char* name :
       {"total_thickness_mm", "meridian", "L1_helical_35_thickness_mm",
        "L1_helical_35_angle_plus_deg", "L1_helical_35_angle_minus_deg",
        "L1_helical_35_length_plus_mm", "L1_helical_35_length_minus_mm", "L2_hoop_thickness_mm",
        "L2_hoop_angle_plus_deg", "L2_hoop_angle_minus_deg"}) {
    ASSERT_TRUE(arrays.count(name)) << name << "\n" << text.substr(0, 400);
  }
  EXPECT_EQ(components["meridian"], 3);
  const std::vector<double>& plus = arrays["L1_helical_35_angle_plus_deg"];
  const std::vector<double>& lplus = arrays["L1_helical_35_length_plus_mm"];
  const std::vector<double>& minus = arrays["L1_helical_35_angle_minus_deg"];
  const std::vector<double>& lminus = arrays["L1_helical_35_length_minus_mm"];
  const std::vector<double>& total = arrays["total_thickness_mm"];
  int checked = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (lplus[f] > 1.0) {
      EXPECT_NEAR(plus[f], kAlpha, 0.1);
      ++checked;
    }
    if (lminus[f] > 1.0) {
      EXPECT_NEAR(minus[f], -kAlpha, 0.1);
    }
    // The meridian of a cylinder's face is the axis.
    EXPECT_NEAR(arrays["meridian"][3 * f + 2], 1.0, 1e-12);
    const double z = mesh.face_centroid(f).z();
    EXPECT_DOUBLE_EQ(total[f], z > 20.0 && z < 180.0 ? 0.9 : 0.5) << f;
  }
  EXPECT_GT(checked, mesh.num_faces() / 8);
}

}  // namespace
}  // namespace windplan
