#include "export/files/layup_export.h"

#include "export/files/laminate_profiles.h"
#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

std::vector<std::string> layup_file_names(const LayupResult& layup, const OutputOptions& output,
                                          const DesignOptions& design) {
  std::vector<std::string> names;
  const bool profiles = layup.revolution && !layup.profiles.surfaces.empty();
  if (output.csv && profiles) names.push_back("layer_profiles.csv");
  if (output.svg && profiles) names.push_back("layer_profiles.svg");
  if (output.csv) names.insert(names.end(), {"laminate.csv", "laminate.vtu"});
  if (design.present && layup.revolution)
    names.insert(names.end(), {"model.inp", "model_plies.csv"});
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

FeaModel layup_fea_model(const LayupResult& layup, const DesignOptions& design) {
  if (!layup.revolution) {
    throw InputError("design: the structural model needs a mandrel that is a shape of revolution");
  }
  const SpindleAxis& axis = layup.mandrel.axis;
  const MeridianPolyline& m = layup.profiles.mandrel;
  const Mesh mesh = revolve_meridian(m, axis, design.fea_edge);
  std::vector<LaminateLayerFaces> faces;
  std::vector<FeaLayerFallback> fallback;
  for (std::size_t k = 0; k < layup.layers.size(); ++k) {
    const LayupLayer& L = layup.layers[k];
    LayerThickness on_mandrel;
    on_mandrel.s = m.s;
    on_mandrel.thickness = layup.profiles.thickness[k].thickness;
    LaminateLayerFaces f;
    f.name = L.summary.name;
    f.kind = L.summary.kind;
    f.thickness.resize(mesh.num_faces());
    for (int i = 0; i < mesh.num_faces(); ++i) {
      const Vec3 c = mesh.face_centroid(i);
      f.thickness[i] = on_mandrel.at(m.project(Vec2(axis.axial(c), axis.radius(c))));
    }
    f.angles = measure_face_angles(mesh, axis, L.circuits);
    faces.push_back(std::move(f));
    FeaLayerFallback fb;
    if (L.options.kind == LayerKind::Helical) {
      fb.clairaut = L.summary.clairaut;
    } else {
      fb.angle = L.summary.angle;
    }
    fallback.push_back(fb);
  }
  FeaModelOptions o;
  o.pressure = design.has_pressure() ? design.pressure : 1.0;
  return build_fea_model(mesh, axis, faces, fallback, o);
}

void write_layup_files(const LayupResult& layup, const OutputOptions& output,
                       const std::filesystem::path& dir, const DesignOptions& design) {
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
  if (design.present && layup.revolution) {
    write_fea_model(dir, layup_fea_model(layup, design), rule_of_mixtures(design.ply),
                    layup.plan.job_name + ": wound laminate under " +
                        (design.has_pressure() ? format_number("%g", design.pressure) : "1") +
                        " MPa (windplan)");
  }
}

}  // namespace windplan
