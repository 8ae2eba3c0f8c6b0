#include "export/files/layup_export.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "export/files/ccx_results.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

// The structural model of configs/vessel_layup.yaml (four layers, measured angles) runs in
// CalculiX without a warning or an error about the input, and its results read back.
TEST(LayupExport, VesselLayupModelRunsInCalculix) {
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "ccx (calculix-ccx) is not installed";
  }
  const Job job = load_job(fs::path(WINDPLAN_SOURCE_DIR) / "configs/vessel_layup.yaml");
  const LayupResult layup = plan_layup(job);
  DesignOptions design;
  design.present = true;
  design.fea_edge = 12.0;
  const FeaModel model = layup_fea_model(layup, design);
  ASSERT_GT(model.elements.size(), 1000u);
  // Every element has plies, two per layer present there; the cylinder's have all four layers.
  std::size_t most = 0;
  for (const std::vector<FeaPly>& p : model.plies) {
    ASSERT_FALSE(p.empty());
    EXPECT_EQ(p.size() % 2, 0u);
    most = std::max(most, p.size());
  }
  EXPECT_EQ(most, 8u);
  const fs::path dir = fs::temp_directory_path() / ("windplan_vl_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_fea_model(dir, model, rule_of_mixtures(design.ply), "vessel_layup");
  const std::string cmd = "cd '" + dir.string() + "' && ccx -i model > ccx.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream log(dir / "ccx.log");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_EQ(text.str().find("WARNING"), std::string::npos) << text.str().substr(0, 2000);
  EXPECT_EQ(text.str().find("ERROR"), std::string::npos) << text.str().substr(0, 2000);
  const CcxResults res = read_ccx_dat(dir / "model.dat");
  const FeaCheck check =
      check_plies(res, read_numeric_csv(dir / "model_plies.csv"), model.layer_names,
                  ply_allowables(rule_of_mixtures(design.ply), 2940.0, 50.0, 70.0),
                  elements_near_free_edges(read_inp_mesh(dir / "model.inp"), 24.0));
  ASSERT_EQ(check.layers.size(), 4u);
  for (const FeaLayerCheck& L : check.layers) {
    EXPECT_GT(L.fibre_strain_mean, 0.0) << L.name;  // 1 MPa inside: the fibres stretch
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace windplan
