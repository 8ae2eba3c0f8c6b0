#include "export/machine/tangent_smoothing.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include <Eigen/Dense>

namespace windplan {

std::vector<Vec3> smooth_tangents(const std::vector<Vec3>& points, const std::vector<double>& s,
                                  const std::vector<double>& curvature,
                                  const std::vector<Vec3>& tangents, double w_max, double w_min,
                                  const std::vector<int>& piece) {
  const int n = static_cast<int>(points.size());
  std::vector<Vec3> out(tangents);
  if (!(w_max > 0.0) || n < 3) return out;
  w_min = std::min(w_min, w_max);
  // First and last index of every piece id, found once: scanning from the polyline's ends for
  // each point made the smoothing quadratic in the circuit's points (most of the export's time).
  // The first index <= i with point i's id is that id's first index overall (i itself has it).
  std::unordered_map<int, std::pair<int, int>> piece_span;
  for (int i = 0; i < static_cast<int>(piece.size()); ++i) {
    auto [it, fresh] = piece_span.try_emplace(piece[i], i, i);
    if (!fresh) it->second.second = i;
  }
  for (int i = 0; i < n; ++i) {
    const double k = curvature[i];
    double w = k > 0.0 ? std::clamp(0.5 / k, w_min, w_max) : w_max;
    // Symmetric windows only (an asymmetric one biases the derivative): shrink near the ends of
    // the polyline and of the point's piece.
    int first = 0, last = n - 1;
    if (!piece.empty()) {
      const std::pair<int, int>& span = piece_span.at(piece[i]);
      first = span.first;
      last = span.second;
    }
    w = std::min({w, s[i] - s[first], s[last] - s[i]});
    const int lo = static_cast<int>(std::lower_bound(s.begin(), s.end(), s[i] - w) - s.begin());
    const int hi = static_cast<int>(std::upper_bound(s.begin(), s.end(), s[i] + w) - s.begin());
    if (hi - lo < 3 || !(w > 0.0)) continue;
    // Normal equations of the quadratic fit in u = (s - s_i) / w (scaled for conditioning). The
    // sums are kept as scalars (M is symmetric): the same products added in the same order as
    // the 3x3 matrix form, so the same bits, at a third of the cost (the export's largest part).
    double m01 = 0.0, m02 = 0.0, m12 = 0.0, m22 = 0.0, m00 = 0.0;
    Vec3 r0 = Vec3::Zero(), r1 = Vec3::Zero(), r2 = Vec3::Zero();  // sum u^j P^T
    for (int j = lo; j < hi; ++j) {
      const double u = (s[j] - s[i]) / w;
      const double u2 = u * u;
      const Vec3 d = points[j] - points[i];
      m00 += 1.0;
      m01 += u;
      m02 += u2;
      m12 += u * u2;
      m22 += u2 * u2;
      r0 += d;
      r1 += u * d;
      r2 += u2 * d;
    }
    Eigen::Matrix3d M;
    M << m00, m01, m02, m01, m02, m12, m02, m12, m22;
    Eigen::Matrix3d R;
    R.row(0) = r0.transpose();
    R.row(1) = r1.transpose();
    R.row(2) = r2.transpose();
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
    if (lu.rank() < 3) continue;
    const Eigen::Matrix3d coef = lu.solve(R);
    Vec3 b = coef.row(1).transpose();
    const double bn = b.norm();
    if (!(bn > 1e-12) || !std::isfinite(bn)) continue;
    b /= bn;
    if (b.dot(tangents[i]) < 0.0) b = -b;
    out[i] = b;
  }
  return out;
}

}  // namespace windplan
