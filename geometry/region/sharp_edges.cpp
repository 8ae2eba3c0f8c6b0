#include "geometry/region/sharp_edges.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

std::string SharpEdges::brief() const {
  return std::to_string(count) + " edges (" + format_fixed(length, 1) + " mm) turning by up to " +
         format_fixed(max_angle_deg, 1) + " deg; " +
         format_fixed(area > 0.0 ? 100.0 * flat_area / area : 0.0, 1) + "% of the area flat";
}

SharpEdges sharp_edges(const Mesh& mesh, double angle_deg) {
  if (!(angle_deg > 0.0 && angle_deg < 180.0)) {
    throw InputError("sharp edges: the angle must lie in (0, 180) degrees");
  }
  SharpEdges out;
  const int F = mesh.num_faces();
  std::vector<Vec3> normal(F);
  std::vector<char> flat(F, 1), valid(F, 0);
  for (int f = 0; f < F; ++f) {
    const double a = mesh.face_area(f);
    out.area += a;
    valid[f] = a > 0.0;
    if (valid[f]) normal[f] = mesh.face_normal(f);
  }
  const double flat_cos = std::cos(0.5 * M_PI / 180.0);
  for (int h = 0; h < 3 * F; ++h) {
    const int f = h / 3, g = mesh.face(mesh.twin(h));
    if (g < 0 || g < f || !valid[f] || !valid[g]) continue;  // each interior edge once
    const double c = std::clamp(normal[f].dot(normal[g]), -1.0, 1.0);
    const double deg = std::acos(c) * 180.0 / M_PI;
    out.max_angle_deg = std::max(out.max_angle_deg, deg);
    if (c < flat_cos) flat[f] = flat[g] = 0;
    if (deg > angle_deg) {
      ++out.count;
      out.length += (mesh.position(mesh.from(h)) - mesh.position(mesh.to(h))).norm();
    }
  }
  for (int f = 0; f < F; ++f) {
    if (flat[f] && valid[f]) out.flat_area += mesh.face_area(f);
  }
  return out;
}

}  // namespace windplan
