#include "geometry/region/planar_end_caps.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/region/mandrel_region.h"

namespace windplan {

bool PlanarEndCapsOptions::is_valid(std::string* why) const {
  if (!(angle_deg > 0.0 && angle_deg < 90.0)) {
    if (why) *why = "planar end caps: angle_deg must be in (0, 90) degrees";
    return false;
  }
  if (!(flatness > 0.0)) {
    if (why) *why = "planar end caps: flatness must be > 0";
    return false;
  }
  return true;
}

std::string PlanarEndCaps::brief() const {
  std::ostringstream s;
  if (!found) return "no two planar patches whose removal leaves an annulus";
  s << "two planar end caps (" << cap_faces[0] << " + " << cap_faces[1] << " faces, " << cap_area[0]
    << " + " << cap_area[1] << " mm^2)";
  return s.str();
}

PlanarEndCaps planar_end_caps(const Mesh& mesh, const std::vector<char>& keep_in,
                              const PlanarEndCapsOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError(why);
  std::vector<char> keep = keep_in;
  if (keep.empty()) keep.assign(mesh.num_faces(), 1);
  if (static_cast<int>(keep.size()) != mesh.num_faces()) {
    throw InputError("planar end caps: " + std::to_string(keep.size()) + " flags for " +
                     std::to_string(mesh.num_faces()) + " faces");
  }
  PlanarEndCaps out;
  const double cos_max = std::cos(options.angle_deg * M_PI / 180.0);
  const double tol = options.flatness * std::max(1e-300, mesh.bounding_box().diagonal_length());
  // Planar patches grown from seeds in face order (deterministic).
  std::vector<int> patch(mesh.num_faces(), -1);
  std::vector<double> area;
  std::vector<std::vector<int>> faces;
  for (int seed = 0; seed < mesh.num_faces(); ++seed) {
    if (!keep[seed] || patch[seed] >= 0 || !(mesh.face_area(seed) > 0.0)) continue;
    const int id = static_cast<int>(area.size());
    const Vec3 n = mesh.face_normal(seed);
    const Vec3 p0 = mesh.face_centroid(seed);
    area.push_back(0.0);
    faces.emplace_back();
    std::vector<int> stack{seed};
    patch[seed] = id;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      area[id] += mesh.face_area(f);
      faces[id].push_back(f);
      for (int k = 0; k < 3; ++k) {
        const int g = mesh.face(mesh.twin(3 * f + k));
        if (g < 0 || !keep[g] || patch[g] >= 0 || !(mesh.face_area(g) > 0.0)) continue;
        if (mesh.face_normal(g).dot(n) < cos_max) continue;
        bool flat = true;
        for (int v : mesh.triangle(g))
          flat = flat && std::abs((mesh.position(v) - p0).dot(n)) <= tol;
        if (!flat) continue;
        patch[g] = id;
        stack.push_back(g);
      }
    }
  }
  if (area.size() < 3) return out;
  std::vector<int> order(area.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });
  std::vector<char> rest = keep;
  for (int k = 0; k < 2; ++k) {
    for (int f : faces[order[k]]) rest[f] = 0;
  }
  // Zero-area faces are in no patch: a sliver inside a cap goes with it when all its
  // edge-neighbours are cap faces.
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (!rest[f] || mesh.face_area(f) > 0.0) continue;
    bool inside_cap = true;
    for (int k = 0; k < 3; ++k) {
      const int g = mesh.face(mesh.twin(3 * f + k));
      inside_cap = inside_cap && g >= 0 && !rest[g];
    }
    if (inside_cap) rest[f] = 0;
  }
  const std::vector<CandidateRegion> parts = candidate_regions(mesh, rest, SpindleAxis{});
  if (parts.size() != 1 || parts[0].loops != 2 || parts[0].genus != 0) return out;
  out.found = true;
  out.keep = std::move(rest);
  for (int k = 0; k < 2; ++k) {
    out.cap_area[k] = area[order[k]];
    out.cap_faces[k] = static_cast<int>(faces[order[k]].size());
  }
  return out;
}

}  // namespace windplan
