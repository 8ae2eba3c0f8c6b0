#pragma once
// Small helpers shared by the SVG plots (export/svg.h, export/axes_svg.h): fixed-decimal numbers,
// XML escapes, tick steps and the circuit colours.
#include <algorithm>
#include <cstddef>
#include <string>

namespace windplan {

/// v with 2 decimals ("-0.00" written as "0.00"), for deterministic SVG coordinates.
std::string f2(double v);

/// XML text escape (&, <, >, "); control characters dropped.
std::string xml_escape(const std::string& s);

/// The smallest of 1, 2, 5 x 10^k at least span / target (a tick step giving about `target`
/// ticks over span).
double nice_step(double span, int target);

/// Golden-angle hue of circuit k (its position in the plan), saturation 0.75, lightness 0.42, as
/// #rrggbb: the colour of circuit k in development.svg and in viewer.html.
std::string circuit_colour(int k);

/// The points attribute of an envelope polyline of n samples (x(i) increasing): per pixel column
/// (px(x) - left, cut into `cols` columns) the entry, lowest, highest and exit samples in order,
/// so a plot of any length keeps its extremes with at most four points a column.
template <typename X, typename Y, typename PX, typename PY>
std::string envelope_points(std::size_t n, X x, Y y, PX px, PY py, double left, int cols) {
  std::string out;
  auto col_of = [&](std::size_t i) {
    return std::clamp(static_cast<int>(px(x(i)) - left), 0, std::max(0, cols - 1));
  };
  std::size_t i = 0;
  while (i < n) {
    const int col = col_of(i);
    std::size_t j = i, jmin = i, jmax = i;
    while (j < n && col_of(j) == col) {
      if (y(j) < y(jmin)) jmin = j;
      if (y(j) > y(jmax)) jmax = j;
      ++j;
    }
    const std::size_t pick[4] = {i, std::min(jmin, jmax), std::max(jmin, jmax), j - 1};
    for (int k = 0; k < 4; ++k) {
      if (k > 0 && pick[k] == pick[k - 1]) continue;
      if (!out.empty()) out += ' ';
      out += f2(px(x(pick[k]))) + "," + f2(py(y(pick[k])));
    }
    i = j;
  }
  return out;
}

}  // namespace windplan
