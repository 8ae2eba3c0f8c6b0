#pragma once
// A feed plan for a sequence of linear machine moves: per-axis velocity and acceleration limits,
// trapezoidal path-speed profiles within blocks, and the time of every block.
//
// The path is the polyline through the machine values q_0 .. q_N (n_axes axes, degrees counted as
// mm); block k (1..N) runs from q_{k-1} to q_k, length l_k = |q_k - q_{k-1}|, unit direction
// d_k. The path speed v(t) starts and ends at rest and within a block follows a trapezoid
// (accelerate, cruise, decelerate) with
//   speed cap      V_k = min_a vmax_a / |d_k,a|  (and the fibre speed cap, when given);
//   path accel     A_k = 0.5 min over blocks k-1, k, k+1 of min_a amax_a / |d_j,a|;
//   corner cap     at the junction of blocks k and k+1, axis a's velocity turns by
//                  v |d_k+1,a - d_k,a|, spread over the two half blocks (time (l_k + l_k+1) / 2v):
//                  v^2 <= 0.25 amax_a (l_k + l_k+1) / |d_k+1,a - d_k,a| (on a circle of radius
//                  rho this is the centripetal limit v^2 <= amax rho / 2); the cap bounds both
//                  blocks' speed, not only the junction.
// Half of each axis's acceleration goes to speed changes, half to direction changes, so that the
// finite-difference acceleration of the block-average axis velocities,
//   (q_k+1,a / T_k+1 - q_k,a / T_k) / ((T_k + T_k+1) / 2)       (q_k,a the move of axis a),
// stays within amax_a on every junction (check_axis_limits measures exactly that, and from and
// to rest at the ends), and every block's average axis velocity within vmax_a. Junction speeds
// come from the usual forward (acceleration) and backward (deceleration) passes.
// Blocks shorter than 1e-6 (mm or deg) take no time and are transparent (the neighbours join across
// them).
#include <array>
#include <vector>

namespace windplan {

struct FeedAxis {
  double max_velocity = 100.0;       ///< mm/s or deg/s, > 0
  double max_acceleration = 1000.0;  ///< mm/s^2 or deg/s^2, > 0
};

using AxisValues = std::array<double, 4>;  ///< machine values of up to 4 axes

struct FeedPlan {
  std::vector<double> duration;  ///< s per point; duration[0] = 0 (the start), [k] of block k
  std::vector<double> speed;     ///< path speed at each point (units/s), 0 at both ends
  double total_time = 0.0;       ///< s
};

/// \param values N + 1 points; \param n_axes 1..4 (the first n_axes entries are used)
/// \param axes limits per axis; \param speed_cap optional per-block extra cap on the path speed
///        (units/s, index k for block k, <= 0 ignored; e.g. from a fibre speed limit)
FeedPlan plan_feed(const std::vector<AxisValues>& values, int n_axes,
                   const std::array<FeedAxis, 4>& axes, const std::vector<double>& speed_cap = {});

/// Time of a trapezoidal move of length l from speed v0 to v1 with cruise speed cap vmax and
/// acceleration a (both > 0); v0, v1 <= vmax and reachable (|v1^2 - v0^2| <= 2 a l).
double trapezoid_time(double l, double v0, double v1, double vmax, double a);

/// The largest ratio of each block's average axis velocity to its limit, and of the junction
/// finite-difference accelerations (see the header comment) to theirs, over all axes.
struct AxisLimitCheck {
  double velocity_ratio = 0.0;                       ///< max |q_k,a| / T_k / vmax_a
  double acceleration_ratio = 0.0;                   ///< max junction acceleration / amax_a
  int velocity_block = -1, acceleration_block = -1;  ///< where (point index), -1 if none
  int velocity_axis = -1, acceleration_axis = -1;
};
AxisLimitCheck check_axis_limits(const std::vector<AxisValues>& values,
                                 const std::vector<double>& duration, int n_axes,
                                 const std::array<FeedAxis, 4>& axes);

}  // namespace windplan
