#include "export/files/ccx_results.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

TEST(CcxResults, ReadsDisplacementsAndPlyValues) {
  const fs::path dir = fs::temp_directory_path() / ("windplan_dat_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "m.dat")
      << "\n displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n"
      << "         1  1.000000E-01  0.000000E+00 -2.000000E-02\n"
      << "\n stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set EALL and time 1.\n\n"
      << "         1   1  1.0E+02 2.0 0.0 0.0 0.0 0.0 O1_1_shell_0\n"
      << "         1   2  3.0E+02 2.0 0.0 0.0 0.0 0.0 O1_1_shell_0\n"
      << "         1   3 -1.0E+02 2.0 0.0 0.0 0.0 0.0 O1_2_shell_0\n"
      << "         1   4 -1.0E+02 2.0 0.0 0.0 0.0 0.0 O1_2_shell_0\n"
      << "\n strains (elem, integ.pnt.,exx,eyy,ezz,exy,exz,eyz) for set EALL and time 1.\n\n"
      << "         1   1  0.010 0.001 0.0 0.0005 0.0 0.0 O1_1_shell_0\n"
      << "         1   2  0.012 0.001 0.0 0.0005 0.0 0.0 O1_1_shell_0\n"
      << "         1   3 -0.002 0.004 0.0 0.0 0.0 0.0 O1_2_shell_0\n"
      << "         1   4 -0.002 0.004 0.0 0.0 0.0 0.0 O1_2_shell_0\n";
  const CcxResults r = read_ccx_dat(dir / "m.dat");
  ASSERT_EQ(r.displacement.size(), 1u);
  EXPECT_DOUBLE_EQ(r.displacement.at(1).z(), -0.02);
  ASSERT_EQ(r.strain.size(), 4u);
  CsvTable plies;
  plies.rows = {{1, 1, 0, 20, 0.1}, {1, 2, 1, -20, 0.1}};
  const FeaCheck c = check_plies(r, plies, {"a", "b"}, {0.02, 0.005, 0.01});
  EXPECT_NEAR(c.layers[0].fibre_strain_max, 0.011, 1e-15);
  EXPECT_NEAR(c.layers[0].fibre_stress_max, 200.0, 1e-12);
  EXPECT_NEAR(c.layers[0].failure_factor, 0.55, 1e-12);  // fibre 0.011 / 0.02
  EXPECT_EQ(c.layers[0].mode, "fibre");
  EXPECT_NEAR(c.layers[1].failure_factor, 0.8, 1e-12);  // transverse 0.004 / 0.005
  EXPECT_EQ(c.governing, "b: transverse");
  plies.rows.push_back({1, 3, 1, 20, 0.1});  // 4 points do not split over 3 plies
  EXPECT_THROW(check_plies(r, plies, {"a", "b"}, {0.02, 0.005, 0.01}), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace windplan
