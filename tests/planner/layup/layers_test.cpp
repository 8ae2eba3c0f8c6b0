#include "planner/layup/layers.h"

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "planner/job/job.h"

namespace windplan {
namespace {

const std::string kMandrel = "mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 300}\n";

std::string error_of(const std::string& yaml) {
  try {
    load_job_from_string(yaml, "/jobs/layup.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Layers, AJobWithoutLayersIsOneHelicalLayerOfWinding) {
  const Job job =
      load_job_from_string(kMandrel + "winding:\n  turns: 3\n  band_width: 7\n", "/jobs/one.yaml");
  EXPECT_TRUE(job.layers.empty());
  const std::vector<LayerOptions> L = effective_layers(job.layers, job.winding);
  ASSERT_EQ(L.size(), 1u);
  EXPECT_EQ(L[0].kind, LayerKind::Helical);
  EXPECT_EQ(L[0].name, "helical1");
  EXPECT_DOUBLE_EQ(L[0].winding.turns, 3.0);
  EXPECT_DOUBLE_EQ(L[0].band_width(), 7.0);
}

TEST(Layers, OrderedListWithDefaultsFromWinding) {
  const Job job = load_job_from_string(
      kMandrel +
          "winding:\n  turns: 2\n  band_width: 8\n  mu: 0.25\n"
          "layers:\n"
          "  - kind: hoop\n    overlap: 1\n"
          "  - kind: helical\n    turns: 0.5\n    name: inner helical\n"
          "  - kind: hoop\n    band_width: 12\n    range: [20, 280]\n    passes: 4\n"
          "  - kind: helical\n    band_width: 6\n",
      "/jobs/layup.yaml");
  ASSERT_EQ(job.layers.size(), 4u);
  const LayerOptions &h1 = job.layers[0], &x1 = job.layers[1], &h2 = job.layers[2],
                     &x2 = job.layers[3];
  EXPECT_EQ(h1.kind, LayerKind::Hoop);
  EXPECT_EQ(h1.name, "hoop1");
  EXPECT_DOUBLE_EQ(h1.hoop.band_width, 8.0);  // from winding
  EXPECT_DOUBLE_EQ(h1.hoop.mu, 0.25);
  EXPECT_DOUBLE_EQ(h1.hoop.pitch(), 7.0);
  EXPECT_FALSE(h1.hoop.has_range());  // the cylindrical part
  EXPECT_EQ(x1.kind, LayerKind::Helical);
  EXPECT_EQ(x1.name, "inner helical");
  EXPECT_DOUBLE_EQ(x1.winding.turns, 0.5);
  EXPECT_DOUBLE_EQ(x1.winding.band_width, 8.0);
  EXPECT_DOUBLE_EQ(x1.winding.mu, 0.25);
  EXPECT_EQ(h2.name, "hoop2");
  EXPECT_DOUBLE_EQ(h2.hoop.x0, 20.0);
  EXPECT_DOUBLE_EQ(h2.hoop.x1, 280.0);
  EXPECT_EQ(h2.hoop.passes, 4);
  EXPECT_DOUBLE_EQ(h2.band_width(), 12.0);
  EXPECT_EQ(x2.name, "helical2");
  EXPECT_DOUBLE_EQ(x2.winding.turns, 2.0);
  EXPECT_DOUBLE_EQ(x2.band_width(), 6.0);
  EXPECT_EQ(effective_layers(job.layers, job.winding).size(), 4u);
}

TEST(Layers, EmptyListIsRejected) {
  const std::string e = error_of(kMandrel + "layers: []\n");
  EXPECT_NE(e.find("'layers'"), std::string::npos) << e;
  EXPECT_NE(e.find("empty"), std::string::npos) << e;
}

TEST(Layers, UnknownKindIsRejected) {
  const std::string e = error_of(kMandrel + "layers:\n  - kind: hoop\n  - kind: polar\n");
  EXPECT_NE(e.find("layers[1].kind"), std::string::npos) << e;
  EXPECT_NE(e.find("'polar' is not one of: helical, hoop"), std::string::npos) << e;
  EXPECT_NE(error_of(kMandrel + "layers:\n  - turns: 2\n").find("needs 'kind"), std::string::npos);
}

TEST(Layers, KeysOfTheOtherKindAreRejected) {
  const std::string e = error_of(kMandrel + "layers:\n  - kind: hoop\n    turns: 3\n");
  EXPECT_NE(e.find("layers[0].turns"), std::string::npos) << e;
  const std::string f = error_of(kMandrel + "layers:\n  - kind: helical\n    overlap: 3\n");
  EXPECT_NE(f.find("layers[0].overlap"), std::string::npos) << f;
}

TEST(Layers, InvalidLayerValuesNameTheLayer) {
  const std::string e =
      error_of(kMandrel + "layers:\n  - kind: hoop\n    band_width: 5\n    overlap: 6\n");
  EXPECT_NE(e.find("layers[0]"), std::string::npos) << e;
  EXPECT_NE(e.find("overlap"), std::string::npos) << e;
  const std::string r = error_of(kMandrel + "layers:\n  - kind: hoop\n    range: [100, 50]\n");
  EXPECT_NE(r.find("range"), std::string::npos) << r;
  const std::string h = error_of(kMandrel + "layers:\n  - kind: helical\n    turns: -1\n");
  EXPECT_NE(h.find("layers[0]"), std::string::npos) << h;
  EXPECT_NE(h.find("turns"), std::string::npos) << h;
}

TEST(Material, Decoded) {
  const Job job = load_job_from_string(
      kMandrel +
          "material:\n  linear_density: 1.65\n  fibre_density: 1.8\n  resin_density: 1.15\n"
          "  fibre_volume_fraction: 0.55\n  band_thickness: 0.3\n",
      "/jobs/m.yaml");
  EXPECT_DOUBLE_EQ(job.material.tex, 1650.0);
  EXPECT_DOUBLE_EQ(job.material.fibre_density, 1.8);
  EXPECT_DOUBLE_EQ(job.material.resin_density, 1.15);
  EXPECT_DOUBLE_EQ(job.material.fibre_volume_fraction, 0.55);
  EXPECT_DOUBLE_EQ(job.material.thickness(10.0), 0.3);
}

TEST(Material, NonPositiveFigureNamesTheKey) {
  for (const char* key : {"tex", "fibre_density", "resin_density", "fibre_volume_fraction", "tows",
                          "band_thickness"}) {
    for (const char* value : {"0", "-1"}) {
      const std::string e = error_of(kMandrel + "material:\n  " + key + ": " + value + "\n");
      EXPECT_NE(e.find(key), std::string::npos) << key << ": " << e;
      EXPECT_NE(e.find("material"), std::string::npos) << e;
    }
  }
  EXPECT_NE(error_of(kMandrel + "material:\n  linear_density: 0\n").find("linear_density"),
            std::string::npos);
  EXPECT_NE(error_of(kMandrel + "material:\n  tows: 2\n  band_thickness: 0.2\n").find("not both"),
            std::string::npos);
  EXPECT_NE(error_of(kMandrel + "material:\n  texx: 800\n").find("material.texx"),
            std::string::npos);
}

}  // namespace
}  // namespace windplan
