#pragma once
// Monotone axes by paying out more fibre: a 4-axis lathe's eye slid outward along its own fibre
// tangent until neither the spindle A nor the carriage X goes back (issue #26).
//
// export/machine/monotone_axes.h makes A and X monotone by replacing them with their
// least-squares monotone fits, which moves the eye off the fibre's tangent line. Where a dwell
// arc on the pins meets its pass that is not noise: the fibre turns at the last pin from the
// arc's circumferential tangent into the pass's helical one, the eye on the pass's tangent drops
// from the envelope over the pins (121.9 mm on the oval canister, whose tabs raise it) to the
// wall's (100 mm) and lies up to 2 deg behind the arc's last eye about the axis. The fit then
// held A there and moved the pass's first eyes up to 6.8 deg round, 2.7 mm below the last pin's
// tangent plane: the fibre left the pins early (replay 0.77 mm off with 21 circuits).
//
// Here, per circuit and in order, an eye whose A or X would go back is moved along its own
// tangent line, E(L) = P + L t with L >= its free length, to the nearest L at which both are
// level with the previous state's (A in the direction of the circuit's net change, X in the
// direction of its piece between the circuit's extremes, as monotone_axes.h cuts it). Along
// the tangent line the angle about the axis changes monotonically and X linearly, so each bound
// is one closed form: for A, the L at which the line crosses the previous eye's meridian half-
// plane, for X the L at which it crosses that eye's station (X only where it steps back more than
// 0.001 mm, ten times the program's last decimal, along a tangent at least 10 deg from
// circumferential: a dwell's line barely moves in X, and levelling a 0.005 mm step there slid an
// eye 100 mm out). The eye stays on the fibre's tangent (the fibre leaves the mandrel where the
// plan lays it, with no lift below its tangent plane), only farther out: its Y and B are
// recomputed, its free length and paid-out length grow by the slide. A state the slide cannot
// level (its tangent slides the wrong way, or beyond `max_slide`) is left for the least-squares
// fit, which is then applied as before (and changes nothing where the slide made the axes
// monotone).
#include <string>
#include <vector>

#include "export/machine/kinematics.h"

namespace windplan {

struct MonotoneByPayoutOptions {
  /// mm: the largest extra free length an eye may be given; beyond it the state is left to the
  /// least-squares fit.
  double max_slide = 200.0;
  bool is_valid(std::string* why) const;
};

struct MonotoneByPayoutSummary {
  int slid = 0;            ///< states whose eye was moved along its tangent
  int left = 0;            ///< states the slide could not level (left to the fit)
  double max_slide = 0.0;  ///< mm, largest extra free length given
  int worst = -1;          ///< index into the states of the largest slide
  std::string brief_report() const;
};

/// Slides the eyes of states[begin, end) (one circuit, in order) along their fibre tangents so
/// that A and X do not go back (see the header comment). Each state's position, direction (unit
/// fibre tangent) and eye must be consistent: eye = position + free_length * direction. Updates
/// eye, a_deg, x_mm, y_mm, b_deg (unwrapped from its old value), radial, free_length, paid_out
/// of the states it slides. `before` (may be null): the state the circuit goes on from (the
/// previous circuit's last, where its dwell arc carries on into this circuit's first pass): the
/// first state is levelled against it too.
/// \throw ConfigError for invalid options.
MonotoneByPayoutSummary monotone_by_payout(const AxisFrame& frame,
                                           std::vector<MachineState>* states, int begin, int end,
                                           const MachineState* before = nullptr,
                                           const MonotoneByPayoutOptions& options = {});

}  // namespace windplan
