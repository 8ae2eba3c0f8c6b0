#include "export/files/layup_export.h"

#include "export/files/laminate_profiles.h"
#include "geometry/base/atomic_file.h"

namespace windplan {

std::vector<std::string> layup_file_names(const LayupResult& layup, const OutputOptions& output) {
  std::vector<std::string> names;
  const bool profiles = layup.revolution && !layup.profiles.surfaces.empty();
  if (output.csv && profiles) names.push_back("layer_profiles.csv");
  if (output.svg && profiles) names.push_back("layer_profiles.svg");
  if (output.csv) names.insert(names.end(), {"laminate.csv", "laminate.vtu"});
  return names;
}

std::vector<LaminateLayerFaces> laminate_faces(const LayupResult& layup) {
  const Mesh& mesh = layup.mandrel.winding.mesh;
  std::vector<LaminateLayerFaces> out;
  for (const LayupLayer& L : layup.layers) {
    LaminateLayerFaces f;
    f.name = L.summary.name;
    f.kind = L.summary.kind;
    f.thickness = L.face_thickness;
    f.angles = measure_face_angles(mesh, layup.mandrel.axis, L.circuits);
    out.push_back(std::move(f));
  }
  return out;
}

void write_layup_files(const LayupResult& layup, const OutputOptions& output,
                       const std::filesystem::path& dir) {
  for (const std::string& name : layup_file_names(layup, output)) {
    if (name == "layer_profiles.csv") {
      write_csv_file(dir / name, laminate_profiles_table(layup.profiles));
    } else if (name == "layer_profiles.svg") {
      write_text_atomically(dir / name, laminate_profiles_svg(layup.profiles));
    }
  }
  if (output.csv) {
    write_laminate_fea(dir, layup.mandrel.winding.mesh, layup.mandrel.axis, laminate_faces(layup));
  }
}

}  // namespace windplan
