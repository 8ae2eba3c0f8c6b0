#include "export/files/fea_deck.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "export/files/ccx_results.h"
#include "geometry/base/errors.h"
#include "planner/plan_layup.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

bool have_ccx() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

// A cylinder of radius R and length L about z as a surface of revolution meshed like a layup's.
Mesh cylinder_mesh(double R, double L, double edge) {
  const MeridianPolyline m =
      MeridianPolyline::from_points({Vec2(0.0, R), Vec2(L, R)}).resampled(edge);
  return revolve_meridian(m, SpindleAxis{}, edge);
}

LaminateLayerFaces uniform_layer(const std::string& name, int faces, double angle, double t) {
  LaminateLayerFaces L;
  L.name = name;
  L.kind = "helical";
  L.thickness.assign(faces, t);
  L.angles.angle_plus.assign(faces, angle);
  L.angles.angle_minus.assign(faces, -angle);
  L.angles.length_plus.assign(faces, 1.0);
  L.angles.length_minus.assign(faces, 1.0);
  return L;
}

TEST(FeaDeck, PliesOrientationsAndClosedEndLoads) {
  const double R = 100.0, L = 300.0, p = 5.0;
  const Mesh mesh = cylinder_mesh(R, L, 25.0);
  const int nf = mesh.num_faces();
  std::vector<LaminateLayerFaces> layers{uniform_layer("helical1", nf, 25.0, 0.6),
                                         uniform_layer("hoop1", nf, 89.0, 0.8)};
  layers[1].angles.length_minus.assign(nf, 0.0);  // one family seen: the other is mirrored
  FeaModelOptions o;
  o.pressure = p;
  const FeaModel M = build_fea_model(mesh, SpindleAxis{}, layers, {{30.0, 0.0}, {0.0, 89.0}}, o);
  ASSERT_EQ(M.elements.size(), static_cast<std::size_t>(nf));
  EXPECT_EQ(M.faces_left_out, 0);
  for (std::size_t e = 0; e < M.elements.size(); ++e) {
    ASSERT_EQ(M.plies[e].size(), 4u);
    EXPECT_NEAR(M.plies[e][0].angle_deg, 25.0, 1e-12);
    EXPECT_NEAR(M.plies[e][1].angle_deg, -25.0, 1e-12);
    EXPECT_NEAR(M.plies[e][3].angle_deg, -89.0, 1e-12);
    EXPECT_NEAR(M.plies[e][2].thickness, 0.4, 1e-12);
    // Fibre directions make the angle with the axis (z) and lie in the shell.
    const Vec3 f = M.plies[e][0].fibre;
    EXPECT_NEAR(std::abs(f.z()), std::cos(25.0 * M_PI / 180.0), 2e-2);
    EXPECT_NEAR(f.dot(M.plies[e][0].across), 0.0, 1e-12);
  }
  // Midside nodes lie on the cylinder.
  for (const auto& el : M.elements) {
    for (int i = 3; i < 6; ++i) {
      EXPECT_NEAR(std::hypot(M.nodes[el[i]].x(), M.nodes[el[i]].y()), R, 1e-9);
    }
  }
  // Each open end carries p pi R^2 (the polygon's area: pi R^2 to the chord error).
  const double ring = 0.5 * 48 * R * R * std::sin(2.0 * M_PI / 48);
  EXPECT_NEAR(M.end_force[0], p * ring, 1e-6 * p * ring);
  EXPECT_NEAR(M.end_force[1], p * ring, 1e-6 * p * ring);
  Vec3 sum = Vec3::Zero();
  for (const FeaModel::Load& l : M.end_loads) sum += l.force;
  EXPECT_NEAR(sum.norm(), 0.0, 1e-6 * p * ring);
  EXPECT_EQ(M.supports.size(), 6u);
  const std::string deck = calculix_deck(M, rule_of_mixtures(FibreResin{}), "test");
  EXPECT_NE(deck.find("*SHELL SECTION, ELSET=E1, COMPOSITE"), std::string::npos);
  EXPECT_NE(deck.find("*ELEMENT, TYPE=S6"), std::string::npos);
  EXPECT_NE(deck.find("** layer 1: hoop1"), std::string::npos);
}

// On a long cylinder of the shipped vessel's radius, CalculiX's hoop and axial membrane strains
// at mid-length agree with classical laminate theory for the same layup within 2 %.
TEST(FeaDeck, CalculixCylinderMatchesLaminateTheory) {
  if (!have_ccx()) GTEST_SKIP() << "ccx (calculix-ccx) is not installed";
  const double R = 100.0, L = 400.0, p = 10.0;
  const Mesh mesh = cylinder_mesh(R, L, 10.0);
  const int nf = mesh.num_faces();
  // Helical, hoop, helical: symmetric but for the +-22 order (an unsymmetric stack bends the
  // shell through its thickness, which membrane CLT leaves out).
  std::vector<LaminateLayerFaces> layers{uniform_layer("helical1", nf, 22.0, 0.25),
                                         uniform_layer("hoop1", nf, 88.5, 0.6),
                                         uniform_layer("helical2", nf, 22.0, 0.25)};
  FeaModelOptions o;
  o.pressure = p;
  const FeaModel M =
      build_fea_model(mesh, SpindleAxis{}, layers, {{0.0, 22.0}, {0.0, 88.5}, {0.0, 22.0}}, o);
  const ElasticConstants ply = rule_of_mixtures(FibreResin{});
  const fs::path dir = fs::temp_directory_path() / ("windplan_fea_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_fea_model(dir, M, ply, "cylinder");
  const std::string cmd = "cd '" + dir.string() + "' && ccx -i model > ccx.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "ccx failed, see " << dir / "ccx.log";
  std::ifstream log(dir / "ccx.log");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_EQ(text.str().find("WARNING"), std::string::npos) << text.str().substr(0, 2000);
  EXPECT_EQ(text.str().find("ERROR"), std::string::npos) << text.str().substr(0, 2000);
  const CcxResults res = read_ccx_dat(dir / "model.dat");

  // Membrane strains of the elements at mid-length (centroids within 50 mm of L/2), from the
  // solver's ply strains (the nodal displacements are not used: see the report of #27).
  const CsvTable plies = read_numeric_csv(dir / "model_plies.csv");
  const std::map<int, Vec3d> membrane = element_membrane_strains(res, plies);
  double hoop = 0.0, axial = 0.0;
  int n = 0;
  for (const auto& [e, eps] : membrane) {
    double z = 0.0;
    for (int i = 0; i < 3; ++i) z += M.nodes[M.elements[e - 1][i]].z() / 3.0;
    if (std::abs(z - 0.5 * L) > 50.0) continue;
    axial += eps[0];
    hoop += eps[1];
    ++n;
  }
  ASSERT_GT(n, 100);
  hoop /= n;
  axial /= n;
  const Vec3d clt = membrane_strains(
      ply,
      {{22.0, 0.125}, {-22.0, 0.125}, {88.5, 0.3}, {-88.5, 0.3}, {22.0, 0.125}, {-22.0, 0.125}},
      {p * R / 2.0, p * R, 0.0});
  EXPECT_NEAR(hoop, clt[1], 0.02 * std::abs(clt[1])) << "ccx " << hoop << " CLT " << clt[1];
  EXPECT_NEAR(axial, clt[0], 0.02 * std::abs(clt[0])) << "ccx " << axial << " CLT " << clt[0];
  std::printf("cylinder R %g: hoop strain ccx %.6g CLT %.6g, axial ccx %.6g CLT %.6g\n", R, hoop,
              clt[1], axial, clt[0]);

  // The ply check reads the same results: the helical plies' fibre strain near CLT's.
  const FeaCheck check =
      check_plies(res, plies, M.layer_names, ply_allowables(ply, 2000.0, 50.0, 70.0));
  const double e1 = ply_strains(clt, 22.0)[0];
  EXPECT_NEAR(check.layers[0].fibre_strain_mean, e1, 0.05 * e1);
  EXPECT_GT(check.failure_factor, 0.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace windplan
