#pragma once
// Monotone machine axes within a circuit: the spindle turns one way, the carriage moves one way
// between its two turning points.
//
// What is left of the tangent noise after smoothing (export/machine/tangent_smoothing.h) still
// reaches the axes multiplied by the free fibre length (hundreds of mm with a lathe2 eye far from a
// dome), as small back-and-forth steps. Here each axis of a circuit is replaced by its
// least-squares monotone fit (isotonic regression, pool-adjacent-violators, O(n)):
//   - A over the whole circuit, in the direction of its net change;
//   - X piecewise: up to the first of its extreme values (the circuit's largest or smallest X,
//     whichever comes first), then the other way to the second, then back to the end — two
//     reversals at most, both where the fibre turns around.
// The change moves the eye off the fibre's tangent line by the size of the noise; the replay
// (export/program/replay.h) measures what that does to the laid fibre.
#include <vector>

namespace windplan {

/// The least-squares non-decreasing (increasing = true) or non-increasing fit of v[begin..end).
void isotonic_fit(std::vector<double>* v, int begin, int end, bool increasing);

/// Makes v[begin..end) monotone between its extremes (see the header comment); returns the
/// largest change made.
double monotone_between_extremes(std::vector<double>* v, int begin, int end);

/// Makes v[begin..end) monotone in the direction of v[end-1] - v[begin]; returns the largest
/// change made.
double monotone_overall(std::vector<double>* v, int begin, int end);

}  // namespace windplan
