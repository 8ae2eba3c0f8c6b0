#include "geometry/region/spine.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/region/plane_section.h"

namespace windplan {

namespace {

// Index i of the segment [s_i, s_{i+1}] holding `at` (clamped) and the fraction along it.
std::size_t segment_at(const Spine& sp, double at, double* t) {
  at = std::clamp(at, 0.0, sp.length());
  const auto it = std::upper_bound(sp.s.begin(), sp.s.end(), at);
  std::size_t i = it == sp.s.begin() ? 0 : static_cast<std::size_t>(it - sp.s.begin()) - 1;
  i = std::min(i, sp.s.size() - 2);
  const double len = sp.s[i + 1] - sp.s[i];
  *t = len > 0.0 ? std::clamp((at - sp.s[i]) / len, 0.0, 1.0) : 0.0;
  return i;
}

}  // namespace

Vec3 Spine::point(double at) const {
  double t = 0.0;
  const std::size_t i = segment_at(*this, at, &t);
  return (1.0 - t) * points[i] + t * points[i + 1];
}

Vec3 Spine::tangent(double at) const {
  double t = 0.0;
  const std::size_t i = segment_at(*this, at, &t);
  return ((1.0 - t) * tangents[i] + t * tangents[i + 1]).normalized();
}

double Spine::project(const Vec3& q, double* distance) const {
  double best = std::numeric_limits<double>::infinity(), at = 0.0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Vec3 a = points[i], ab = points[i + 1] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - q).squaredNorm();
    if (d < best) best = d, at = s[i] + t * (s[i + 1] - s[i]);
  }
  if (distance) *distance = std::sqrt(best);
  return at;
}

Spine spine_from_polyline(const std::vector<Vec3>& pts) {
  if (pts.size() < 2) throw InputError("spine: a centre line needs at least 2 points");
  Spine sp;
  sp.points = pts;
  sp.s.push_back(0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double d = (pts[i] - pts[i - 1]).norm();
    if (!(d > 0.0)) {
      throw InputError("spine: centre-line points " + std::to_string(i - 1) + " and " +
                       std::to_string(i) + " coincide");
    }
    sp.s.push_back(sp.s.back() + d);
  }
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = pts[i == 0 ? 0 : i - 1], b = pts[i + 1 == n ? n - 1 : i + 1];
    sp.tangents.push_back((b - a).normalized());
  }
  return sp;
}

Vec3 loop_centroid(const std::vector<Vec3>& loop) {
  Vec3 c = Vec3::Zero(), mean = Vec3::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3& a = loop[i];
    const Vec3& b = loop[(i + 1) % loop.size()];
    const double len = (b - a).norm();
    c += 0.5 * len * (a + b);
    total += len;
    mean += a;
  }
  if (total > 0.0) return c / total;
  return loop.empty() ? mean : Vec3(mean / static_cast<double>(loop.size()));
}

bool SpineOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (!std::isnan(step) && !(step > 0.0 && std::isfinite(step))) return fail("step must be > 0 mm");
  if (iterations < 1) return fail("iterations must be >= 1");
  if (max_sections < 2) return fail("max_sections must be >= 2");
  return true;
}

std::string SpineSummary::brief_report() const {
  return std::to_string(sections) + " sections " + format_number("%.2f", step) +
         " mm apart, mean radius " + format_number("%.2f", mean_radius) + " mm, cuts within " +
         format_number("%.2f", max_tilt_deg) + " deg of normal";
}

SpineResult extract_spine(const Mesh& m, const std::array<std::vector<int>, 2>& loops,
                          const SpindleAxis& axis, const SpineOptions& options,
                          const std::string& what) {
  if (std::string why; !options.is_valid(&why)) throw ConfigError("spine: " + why);
  std::array<Vec3, 2> end_c;
  double mean_r = 0.0;
  int nr = 0;
  for (int e = 0; e < 2; ++e) {
    if (loops[e].size() < 3) throw InputError(what + ": a boundary loop has fewer than 3 vertices");
    std::vector<Vec3> pts;
    for (int v : loops[e]) pts.push_back(m.position(v));
    end_c[e] = loop_centroid(pts);
    for (const Vec3& p : pts) mean_r += (p - end_c[e]).norm(), ++nr;
  }
  mean_r /= nr;
  SpineResult res;
  res.summary.mean_radius = mean_r;
  const double h = std::isnan(options.step) ? 0.25 * mean_r : options.step;
  res.summary.step = h;
  // The start direction: the start loop's plane normal (the least-variance direction of its
  // points), oriented towards the end loop.
  Vec3 t;
  {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (int v : loops[0]) {
      const Vec3 d = m.position(v) - end_c[0];
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    t = es.eigenvectors().col(0).normalized();
    if (t.dot(end_c[1] - end_c[0]) < 0.0) t = -t;
  }
  const PlaneSectioner sectioner(m, axis);
  std::vector<Vec3> centres{end_c[0]};
  Vec3 c = end_c[0];
  while (true) {
    // Stop when the end loop's centre is within a step ahead.
    const Vec3 to_end = end_c[1] - c;
    if (to_end.norm() < 1.5 * h && centres.size() > 1) break;
    if (static_cast<int>(centres.size()) >= options.max_sections) {
      throw InputError(what + ": more than " + std::to_string(options.max_sections) +
                       " sections without reaching the end loop (not a tube?)");
    }
    Vec3 p = c + h * t, n = t;
    Vec3 next = p;
    for (int it = 0; it < options.iterations; ++it) {
      PlaneSection sec;
      if (!sectioner.around_loop(n, n.dot(p), &p, &sec)) {
        throw InputError(what + ": the section normal to the centre line " +
                         format_number("%.1f", h * centres.size()) +
                         " mm from the start loop does not go around the tube (at " +
                         format_number("%.1f", p.x()) + ", " + format_number("%.1f", p.y()) + ", " +
                         format_number("%.1f", p.z()) + " mm): the region is not a tube, " +
                         "or it bends tighter than the step follows");
      }
      next = loop_centroid(sec.points);
      const Vec3 chord = (next - c).normalized();
      if (it + 1 == options.iterations) {
        const double tilt = std::acos(std::clamp(chord.dot(n), -1.0, 1.0)) * 180.0 / M_PI;
        res.summary.max_tilt_deg = std::max(res.summary.max_tilt_deg, tilt);
      }
      // Next cut: through the new centre, normal to the chord from the last centre.
      n = chord;
      p = next;
      ++res.summary.sections;
    }
    // The tangent at the new centre: the chord turned on by the same amount it turned from t.
    const Vec3 chord = (next - c).normalized();
    t = (2.0 * chord - t).normalized();
    c = next;
    centres.push_back(c);
  }
  centres.push_back(end_c[1]);
  res.spine = spine_from_polyline(centres);
  return res;
}

}  // namespace windplan
