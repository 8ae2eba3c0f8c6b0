#include "export/machine/tangent_smoothing.h"

#include <algorithm>
#include <cmath>

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
  for (int i = 0; i < n; ++i) {
    const double k = curvature[i];
    double w = k > 0.0 ? std::clamp(0.5 / k, w_min, w_max) : w_max;
    // Symmetric windows only (an asymmetric one biases the derivative): shrink near the ends of
    // the polyline and of the point's piece.
    int first = 0, last = n - 1;
    if (!piece.empty()) {
      while (first < i && piece[first] != piece[i]) ++first;
      while (last > i && piece[last] != piece[i]) --last;
    }
    w = std::min({w, s[i] - s[first], s[last] - s[i]});
    const int lo = static_cast<int>(std::lower_bound(s.begin(), s.end(), s[i] - w) - s.begin());
    const int hi = static_cast<int>(std::upper_bound(s.begin(), s.end(), s[i] + w) - s.begin());
    if (hi - lo < 3 || !(w > 0.0)) continue;
    // Normal equations of the quadratic fit in u = (s - s_i) / w (scaled for conditioning).
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();  // rows: sum u^j P^T
    for (int j = lo; j < hi; ++j) {
      const double u = (s[j] - s[i]) / w;
      const double pw[3] = {1.0, u, u * u};
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) M(r, c) += pw[r] * pw[c];
        R.row(r) += pw[r] * (points[j] - points[i]).transpose();
      }
    }
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
