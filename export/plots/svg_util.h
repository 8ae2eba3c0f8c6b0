#pragma once
// Small helpers shared by the SVG plots (export/plots/svg.h, export/plots/axes_svg.h):
// fixed-decimal numbers, XML escapes, tick steps and the circuit colours.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
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

/// A panel's value grid: about four faint horizontal lines from `left` over `width` px at tick
/// values of [lo, hi] (py maps a value to y), each labelled at its left.
template <typename PY>
std::string value_grid(double lo, double hi, double left, double width, PY py) {
  std::string out;
  const double step = nice_step(hi - lo, 4);
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%g", std::fabs(v) < 1e-9 * step ? 0.0 : v);
    out += "<line x1=\"" + f2(left) + "\" y1=\"" + f2(py(v)) + "\" x2=\"" + f2(left + width) +
           "\" y2=\"" + f2(py(v)) + "\" stroke=\"#eee\" stroke-width=\"0.5\"/>\n<text x=\"" +
           f2(left - 4) + "\" y=\"" + f2(py(v) + 3) + "\" text-anchor=\"end\">" + buf + "</text>\n";
  }
  return out;
}

/// The shared horizontal axis under the panels: about ten tick labels over [0, end] (px maps a
/// value to x) at y = bottom + 16 and the caption (XML text) centred under them.
template <typename PX>
std::string bottom_axis(double end, double bottom, double left, double width, PX px,
                        const std::string& caption) {
  std::string out = "<g font-family=\"sans-serif\" font-size=\"11\" fill=\"#333\">\n";
  const double step = nice_step(end, 10);
  for (double t = 0.0; t <= end + 1e-9 * step; t += step) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%g", t);
    out += "<text x=\"" + f2(px(t)) + "\" y=\"" + f2(bottom + 16) + "\" text-anchor=\"middle\">" +
           buf + "</text>\n";
  }
  out += "<text x=\"" + f2(left + width / 2) + "\" y=\"" + f2(bottom + 38) +
         "\" text-anchor=\"middle\" font-size=\"13\">" + caption + "</text>\n</g>\n";
  return out;
}

}  // namespace windplan
