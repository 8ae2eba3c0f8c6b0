#pragma once
// The laminate files of a layup (planner/plan_layup.h), written beside the plan's files:
//   layer_profiles.csv, layer_profiles.svg  the meridian profiles and thickness of each layer
//                                           (shapes of revolution;
//                                           export/files/laminate_profiles.h), with output.csv /
//                                           output.svg;
//   laminate.csv, laminate.vtu              per face of the mandrel's winding surface and per
//                                           layer: fibre angles measured from the layer's paths
//                                           and thickness (export/files/laminate_fea.h), with
//                                           output.csv.
#include <filesystem>
#include <string>
#include <vector>

#include "export/files/laminate_fea.h"
#include "planner/job/job.h"
#include "planner/plan_layup.h"

namespace windplan {

/// The names write_layup_files writes, in order.
std::vector<std::string> layup_file_names(const LayupResult& layup, const OutputOptions& output);

/// Per layer, its fibre angles and thickness on the faces of the mandrel's winding surface.
std::vector<LaminateLayerFaces> laminate_faces(const LayupResult& layup);

/// Writes the files of layup_file_names into `dir`. \throw IoError
void write_layup_files(const LayupResult& layup, const OutputOptions& output,
                       const std::filesystem::path& dir);

}  // namespace windplan
