#include "export/machine/feed_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace windplan {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

double trapezoid_time(double l, double v0, double v1, double vmax, double a) {
  if (!(l > 0.0)) return 0.0;
  const double peak = std::sqrt(std::max(0.0, (2.0 * a * l + v0 * v0 + v1 * v1) / 2.0));
  const double vp = std::max({std::min(vmax, peak), v0, v1, 1e-12});
  const double d_acc = (vp * vp - v0 * v0) / (2.0 * a);
  const double d_dec = (vp * vp - v1 * v1) / (2.0 * a);
  const double cruise = std::max(0.0, l - d_acc - d_dec);
  return (vp - v0) / a + (vp - v1) / a + cruise / vp;
}

FeedPlan plan_feed(const std::vector<AxisValues>& values, int n_axes,
                   const std::array<FeedAxis, 4>& axes, const std::vector<double>& speed_cap) {
  FeedPlan fp;
  const int n = static_cast<int>(values.size());
  fp.duration.assign(std::max(n, 0), 0.0);
  fp.speed.assign(std::max(n, 0), 0.0);
  if (n < 2) return fp;
  // The blocks of non-zero length, with their lengths and directions.
  std::vector<int> blk;  // point index k of block k
  std::vector<double> len;
  std::vector<AxisValues> dir;
  for (int k = 1; k < n; ++k) {
    double l2 = 0.0;
    for (int a = 0; a < n_axes; ++a) l2 += std::pow(values[k][a] - values[k - 1][a], 2);
    if (!(l2 > 1e-12)) continue;  // below 1e-6 mm (or deg): no motion, no time
    const double l = std::sqrt(l2);
    AxisValues d{0, 0, 0, 0};
    for (int a = 0; a < n_axes; ++a) d[a] = (values[k][a] - values[k - 1][a]) / l;
    blk.push_back(k);
    len.push_back(l);
    dir.push_back(d);
  }
  const int m = static_cast<int>(blk.size());
  if (m == 0) return fp;
  std::vector<double> cap(m, kInf), acc(m, kInf);
  for (int j = 0; j < m; ++j) {
    for (int a = 0; a < n_axes; ++a) {
      const double da = std::fabs(dir[j][a]);
      if (da > 0.0) {
        cap[j] = std::min(cap[j], axes[a].max_velocity / da);
        acc[j] = std::min(acc[j], axes[a].max_acceleration / da);
      }
    }
    const int k = blk[j];
    if (k < static_cast<int>(speed_cap.size()) && speed_cap[k] > 0.0) {
      cap[j] = std::min(cap[j], speed_cap[k]);
    }
  }
  // Corner caps bound both blocks of a junction.
  for (int j = 0; j + 1 < m; ++j) {
    for (int a = 0; a < n_axes; ++a) {
      const double turn = std::fabs(dir[j + 1][a] - dir[j][a]);
      if (turn > 1e-15) {
        const double v = std::sqrt(0.25 * axes[a].max_acceleration * (len[j] + len[j + 1]) / turn);
        cap[j] = std::min(cap[j], v);
        cap[j + 1] = std::min(cap[j + 1], v);
      }
    }
  }
  std::vector<double> a_path(m);
  for (int j = 0; j < m; ++j) {
    double a = acc[j];
    if (j > 0) a = std::min(a, acc[j - 1]);
    if (j + 1 < m) a = std::min(a, acc[j + 1]);
    a_path[j] = 0.5 * a;
  }
  // Junction speeds: w[j] at the end of block j (w[-1] = start = 0, w[m-1] = 0).
  std::vector<double> w(m, 0.0);
  for (int j = 0; j + 1 < m; ++j) w[j] = std::min(cap[j], cap[j + 1]);
  double prev = 0.0;
  for (int j = 0; j < m; ++j) {
    w[j] = std::min(w[j], std::sqrt(prev * prev + 2.0 * a_path[j] * len[j]));
    prev = w[j];
  }
  w[m - 1] = 0.0;
  for (int j = m - 2; j >= 0; --j) {
    w[j] = std::min(w[j], std::sqrt(w[j + 1] * w[j + 1] + 2.0 * a_path[j + 1] * len[j + 1]));
  }
  double t = 0.0;
  for (int j = 0; j < m; ++j) {
    const double v0 = j == 0 ? 0.0 : w[j - 1];
    const double dt = trapezoid_time(len[j], v0, w[j], cap[j], a_path[j]);
    fp.duration[blk[j]] = dt;
    fp.speed[blk[j]] = w[j];
    t += dt;
  }
  fp.total_time = t;
  return fp;
}

AxisLimitCheck check_axis_limits(const std::vector<AxisValues>& values,
                                 const std::vector<double>& duration, int n_axes,
                                 const std::array<FeedAxis, 4>& axes) {
  AxisLimitCheck c;
  const int n = static_cast<int>(values.size());
  // Average axis velocities of the blocks that take time, with rest before and after.
  std::vector<int> idx;
  for (int k = 1; k < n; ++k) {
    if (duration[k] > 0.0) idx.push_back(k);
  }
  auto vel = [&](int k, int a) { return (values[k][a] - values[k - 1][a]) / duration[k]; };
  for (std::size_t j = 0; j < idx.size(); ++j) {
    for (int a = 0; a < n_axes; ++a) {
      const double r = std::fabs(vel(idx[j], a)) / axes[a].max_velocity;
      if (r > c.velocity_ratio) {
        c.velocity_ratio = r;
        c.velocity_block = idx[j];
        c.velocity_axis = a;
      }
    }
  }
  for (std::size_t j = 0; j <= idx.size(); ++j) {
    const bool has_prev = j > 0, has_next = j < idx.size();
    if (!has_prev && !has_next) break;
    const double t0 = has_prev ? duration[idx[j - 1]] : 0.0;
    const double t1 = has_next ? duration[idx[j]] : 0.0;
    for (int a = 0; a < n_axes; ++a) {
      const double v0 = has_prev ? vel(idx[j - 1], a) : 0.0;
      const double v1 = has_next ? vel(idx[j], a) : 0.0;
      const double r = std::fabs(v1 - v0) / (0.5 * (t0 + t1)) / axes[a].max_acceleration;
      if (r > c.acceleration_ratio) {
        c.acceleration_ratio = r;
        c.acceleration_block = has_next ? idx[j] : idx[j - 1];
        c.acceleration_axis = a;
      }
    }
  }
  return c;
}

}  // namespace windplan
