#include "export/plots/unroll.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/base/errors.h"

namespace windplan {

namespace {
constexpr double kPi = 3.14159265358979323846;

double wrap_deg(double d) {
  d = std::fmod(d, 360.0);
  if (d < 0.0) d += 360.0;
  return d >= 360.0 ? 0.0 : d;
}
}  // namespace

Unrolling Unrolling::make(const WindingPlan& plan, const Mesh& mandrel,
                          const std::vector<int>* face_map, std::optional<bool> revolution) {
  Unrolling u;
  u.frame_ = make_axis_frame(plan.axis);
  // A shape of revolution (the planner found its geodesic turn limit): the spindle axis is its own.
  if (revolution ? *revolution : !std::isnan(plan.metrics.geodesic_turn_limit)) return u;
  const std::vector<std::vector<int>> loops = mandrel.boundary_loops();
  if (loops.size() != 2) {
    u.fallback_reason = "the mandrel has " + std::to_string(loops.size()) +
                        " boundary loops, not 2: unrolled about the spindle axis";
    return u;
  }
  try {
    std::array<std::vector<int>, 2> lv = {mandrel.loop_vertices(loops[0]),
                                          mandrel.loop_vertices(loops[1])};
    // h = 0 on the loop at the lower axial position (the start loop of the winding surface), as
    // the planner's harmonic height, so that coverage levels read the same here.
    auto mean_axial = [&](const std::vector<int>& l) {
      double a = 0.0;
      for (int v : l) a += u.frame_.axial(mandrel.position(v));
      return l.empty() ? 0.0 : a / static_cast<double>(l.size());
    };
    if (mean_axial(lv[0]) > mean_axial(lv[1])) std::swap(lv[0], lv[1]);
    u.hc_ = compute_harmonic_coordinates(mandrel, lv);
    double perimeter = 0.0;
    for (const auto& l : lv)
      for (std::size_t i = 0; i < l.size(); ++i)
        perimeter += (mandrel.position(l[(i + 1) % l.size()]) - mandrel.position(l[i])).norm();
    u.length_ = mandrel.total_area() / (perimeter / 2.0);
    u.mesh_ = mandrel;
    if (face_map) {
      for (std::size_t f = 0; f < face_map->size(); ++f) {
        const int g = (*face_map)[f];
        if (g < 0) continue;
        if (g >= static_cast<int>(u.hint_face_.size())) u.hint_face_.resize(g + 1, -1);
        u.hint_face_[g] = static_cast<int>(f);
      }
    }
    u.kind_ = Kind::Conformal;
  } catch (const InputError& e) {
    u.fallback_reason =
        std::string("no conformal coordinates (") + e.what() + "): unrolled about the spindle axis";
  }
  return u;
}

std::string Unrolling::along_title() const {
  if (kind_ == Kind::Axis) return "axial position x [mm]";
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "height between the ends h L [mm] (h harmonic, 0 to 1; L = %.1f mm = area / mean "
                "end perimeter)",
                length_);
  return buf;
}

std::string Unrolling::around_title() const {
  return kind_ == Kind::Axis ? "angle about spindle axis [deg]" : "angle around [deg]";
}

// Barycentric coordinates of p projected onto the plane of face f (unclamped; false for a
// degenerate face).
bool Unrolling::barycentric(const Vec3& p, int f, Vec3* bary) const {
  const auto& t = mesh_.triangle(f);
  const Vec3 a = mesh_.position(t[0]), b = mesh_.position(t[1]), c = mesh_.position(t[2]);
  const Vec3 e0 = b - a, e1 = c - a, q = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = q.dot(e0), d21 = q.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0.0)) return false;
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  *bary = Vec3(1.0 - v - w, v, w);
  return true;
}

// Distance from p to the point of face f at the clamped barycentric coordinates (close to the
// true point-triangle distance, exact inside).
double Unrolling::face_distance(const Vec3& p, int f, Vec3* bary) const {
  if (!barycentric(p, f, bary)) return std::numeric_limits<double>::infinity();
  Vec3 c = bary->cwiseMax(0.0);
  c /= c.sum();
  const auto& t = mesh_.triangle(f);
  const Vec3 q =
      c[0] * mesh_.position(t[0]) + c[1] * mesh_.position(t[1]) + c[2] * mesh_.position(t[2]);
  return (q - p).norm();
}

int Unrolling::locate(const Vec3& p, int hint, Vec3* bary) const {
  const int face = hint_face_.empty()                                        ? hint
                   : hint >= 0 && hint < static_cast<int>(hint_face_.size()) ? hint_face_[hint]
                                                                             : -1;
  if (face >= 0 && face < mesh_.num_faces() && barycentric(p, face, bary) &&
      bary->minCoeff() > -1e-3) {
    const auto& t = mesh_.triangle(face);
    const double scale = (mesh_.position(t[1]) - mesh_.position(t[0])).norm() +
                         (mesh_.position(t[2]) - mesh_.position(t[0])).norm();
    if (face_distance(p, face, bary) <= 1e-2 * scale + 1e-9) {
      barycentric(p, face, bary);
      return face;
    }
  }
  // Near the last point located (consecutive points of a path or cut-line are close): the faces
  // round the vertices of its face; one that holds p is taken.
  if (last_face_ >= 0) {
    const auto& t = mesh_.triangle(last_face_);
    const double scale = (mesh_.position(t[1]) - mesh_.position(t[0])).norm() +
                         (mesh_.position(t[2]) - mesh_.position(t[0])).norm();
    for (int k = 0; k < 3; ++k) {
      for (int h : mesh_.outgoing_halfedges(t[k])) {
        const int g = mesh_.face(h);
        if (g < 0 || !barycentric(p, g, bary) || bary->minCoeff() < -1e-3) continue;
        if (face_distance(p, g, bary) <= 1e-2 * scale + 1e-9) {
          barycentric(p, g, bary);
          last_face_ = g;
          return g;
        }
      }
    }
  }
  // The closest face of all.
  int best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh_.num_faces(); ++f) {
    Vec3 b;
    const double d = face_distance(p, f, &b);
    if (d < bd) {
      bd = d;
      best = f;
    }
  }
  last_face_ = best;
  barycentric(p, best, bary);
  *bary = bary->cwiseMax(0.0);
  *bary /= bary->sum();
  return best;
}

Vec2 Unrolling::eval(int f, const Vec3& bary) const {
  const auto& t = mesh_.triangle(f);
  double h = 0.0, th = 0.0;
  for (int k = 0; k < 3; ++k) {
    h += bary[k] * hc_.height[t[k]];
    th += bary[k] * hc_.corner_theta(mesh_, f, k);
  }
  return Vec2(h * length_, wrap_deg(th * 180.0 / kPi));
}

Vec2 Unrolling::map(const Vec3& p, int face) const {
  if (kind_ == Kind::Axis) {
    return Vec2(frame_.axial(p), wrap_deg(frame_.angle(p) * 180.0 / kPi));
  }
  Vec3 bary;
  const int f = locate(p, face, &bary);
  return eval(f, bary);
}

Vec2 Unrolling::map_offset(const Vec3& anchor, int face, const Vec3& q) const {
  if (kind_ == Kind::Axis) return map(q);
  Vec3 bary;
  const int f = locate(anchor, face, &bary);
  barycentric(q, f, &bary);  // unclamped: the face's linear map extended to q
  return eval(f, bary);
}

}  // namespace windplan
