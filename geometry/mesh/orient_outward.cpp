#include "geometry/mesh/orient_outward.h"

#include <cmath>
#include <utility>
#include <vector>

#include "geometry/base/errors.h"

namespace windplan {

bool OrientOutwardOptions::is_valid(std::string* why) const {
  if (!(volume_tolerance >= 0.0) || !std::isfinite(volume_tolerance)) {
    if (why) *why = "volume_tolerance must be finite and >= 0";
    return false;
  }
  return true;
}

std::string OrientOutwardSummary::brief_report() const {
  std::string s = std::to_string(flipped_components) + " of " + std::to_string(components) +
                  " component(s) pointed inward";
  if (flipped_faces > 0) s += ": " + std::to_string(flipped_faces) + " triangles reversed";
  if (undecided > 0) s += "; " + std::to_string(undecided) + " undecided (no enclosed volume)";
  return s;
}

double capped_signed_volume(const Mesh& mesh, const std::vector<int>& face_component,
                            int component) {
  // Relative to a point of the component: the sum over a closed surface does not depend on it,
  // and the terms stay small.
  Vec3 origin = Vec3::Zero();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (face_component[f] == component) {
      origin = mesh.position(mesh.triangle(f)[0]);
      break;
    }
  }
  auto det = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    return (a - origin).dot((b - origin).cross(c - origin));
  };
  double six_v = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (face_component[f] != component) continue;
    const Tri& t = mesh.triangle(f);
    six_v += det(mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2]));
  }
  // Caps: each boundary loop (boundary halfedges run opposite to their faces' edges, so a fan
  // along them continues the orientation) fanned to its centroid.
  std::vector<char> seen(mesh.num_halfedges(), 0);
  for (int h = mesh.num_interior_halfedges(); h < mesh.num_halfedges(); ++h) {
    if (seen[h] || face_component[mesh.face(mesh.twin(h))] != component) continue;
    std::vector<int> loop;
    for (int b = h; !seen[b]; b = mesh.next(b)) {
      seen[b] = 1;
      loop.push_back(b);
    }
    Vec3 centre = Vec3::Zero();
    for (int b : loop) centre += mesh.position(mesh.from(b));
    centre /= double(loop.size());
    for (int b : loop) six_v += det(mesh.position(mesh.from(b)), mesh.position(mesh.to(b)), centre);
  }
  return six_v / 6.0;
}

OrientOutwardResult orient_outward(const Mesh& mesh, const OrientOutwardOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("orient_outward: " + why);
  OrientOutwardResult r;
  int count = 0;
  const std::vector<int> comp = mesh.face_components(&count);
  r.summary.components = count;
  const double d = mesh.bounding_box().diagonal_length();
  std::vector<char> flip(count, 0);
  for (int c = 0; c < count; ++c) {
    const double v = capped_signed_volume(mesh, comp, c);
    if (std::fabs(v) <= options.volume_tolerance * d * d * d) {
      ++r.summary.undecided;
    } else if (v < 0.0) {
      flip[c] = 1;
      ++r.summary.flipped_components;
    }
  }
  if (r.summary.flipped_components == 0) {
    r.mesh = mesh;
    return r;
  }
  TriangleSoup soup{mesh.points(), mesh.triangles()};
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (!flip[comp[f]]) continue;
    std::swap(soup.triangles[f][1], soup.triangles[f][2]);
    ++r.summary.flipped_faces;
  }
  r.mesh = Mesh(std::move(soup));
  return r;
}

}  // namespace windplan
