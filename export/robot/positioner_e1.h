#pragma once
// The positioner's E1 for a robot cell: monotone within every circuit (so within every pass), and
// smooth (issue #26 follow-up).
//
// In a robot cell the eye's place in the mandrel frame is fixed by the plan (E = P + L t,
// export/machine/kinematics.h); E1 only decides where in the cell the arm must put it: the eye
// at angle theta(E) about the E1 axis in the mandrel frame lies at theta(E) + E1 in the positioner
// frame. The lathe model's spindle angle A = -theta(E) (unwrapped) puts every eye in the half-plane
// y > 0, z = 0 of the positioner frame, but on a bent tube it wobbles back and forth with the
// tube's bends (bent_tube: 306 reversals inside passes), which a winding engineer would not
// accept from a mandrel (fibre tension, backlash, cycle time). Here, per circuit:
//   1. the least-squares monotone fit of A in the direction of its net change over the circuit
//      (isotonic regression, pool-adjacent-violators: export/machine/monotone_axes.h), the
//      monotone sequence closest to A, so the arm takes up as little as it can;
//   2. two passes of a moving average over the states within +-smoothing seconds of the lathe
//      model's time t_s (a window whose ends only move forward keeps a monotone sequence monotone),
//      so that E1 has no steps where the fit pools.
// The arm then puts the eye at delta = E1 - A about the E1 axis (export/robot/robot_motion.h).
// Reversals are counted as kinematics.h counts them: a sign change between consecutive moves
// larger than 1e-9 deg, "in a pass" when the state is strictly inside a Pass segment.
#include <string>
#include <vector>

#include "export/machine/kinematics.h"

namespace windplan {

struct PositionerE1Options {
  double smoothing = 0.5;  ///< s, half-width of the moving average in the lathe model's time, >= 0
  bool is_valid(std::string* why) const;
};

struct PositionerE1 {
  std::vector<double> e1;             ///< deg, one per Motion::states
  double max_offset = 0.0;            ///< deg, largest |E1 - A| (what the arm takes up)
  int reversals_in_passes = 0;        ///< of E1
  int a_reversals_in_passes = 0;      ///< of the lathe model's A (what E1 = A would do)
  int max_reversals_per_circuit = 0;  ///< of E1
  std::string brief_report() const;
};

/// E1 reversals strictly inside passes of the plan, for values v (deg) per Motion::states.
int reversals_in_passes(const Motion& motion, const WindingPlan& plan, const std::vector<double>& v,
                        int* max_per_circuit = nullptr);

/// \throw ConfigError for invalid options
PositionerE1 fit_positioner_e1(const Motion& motion, const WindingPlan& plan,
                               const PositionerE1Options& options = {});

}  // namespace windplan
