#pragma once
// Small helpers shared by the SVG plots (export/svg.h, export/axes_svg.h): fixed-decimal numbers,
// XML escapes, tick steps and the circuit colours.
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

}  // namespace windplan
