#pragma once
// The laminate files of a layup (planner/plan_layup.h), written beside the plan's files:
//   layer_profiles.csv, layer_profiles.svg  the meridian profiles and thickness of each layer
//                                           (shapes of revolution;
//                                           export/files/laminate_profiles.h), with output.csv /
//                                           output.svg;
//   laminate.csv, laminate.vtu              per face of the mandrel's winding surface and per
//                                           layer: fibre angles measured from the layer's paths
//                                           and thickness (export/files/laminate_fea.h), with
//                                           output.csv;
//   model.inp, model_plies.csv              with a `design:` section (shapes of revolution): the
//                                           structural model CalculiX runs
//                                           (export/files/fea_deck.h) on the mandrel's meridian
//                                           revolved with design.fea_edge, under
//                                           design.pressure (1 MPa when none is given).
#include <filesystem>
#include <string>
#include <vector>

#include "export/files/fea_deck.h"
#include "export/files/laminate_fea.h"
#include "planner/job/job.h"
#include "planner/plan_layup.h"

namespace windplan {

/// The names write_layup_files writes, in order.
std::vector<std::string> layup_file_names(const LayupResult& layup, const OutputOptions& output,
                                          const DesignOptions& design = {});

/// The structural model of a layup on a shape of revolution (header comment).
/// \throw InputError off shapes of revolution; what build_fea_model throws.
FeaModel layup_fea_model(const LayupResult& layup, const DesignOptions& design);

/// Per layer, its fibre angles and thickness on the faces of the mandrel's winding surface.
std::vector<LaminateLayerFaces> laminate_faces(const LayupResult& layup);

/// Writes the files of layup_file_names into `dir`. \throw IoError
void write_layup_files(const LayupResult& layup, const OutputOptions& output,
                       const std::filesystem::path& dir, const DesignOptions& design = {});

}  // namespace windplan
