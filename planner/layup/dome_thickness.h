#pragma once
// A helical layer's thickness that stays finite at the turnaround: fibre continuity away from it,
// a cubic near it (the cubic-spline method of the winding literature, e.g. Wang et al., Composite
// Structures 2011; Vasiliev & Morozov 2007 ch. 7, for the band-width region at the polar opening).
//
// Fibre continuity (planner/layup/laminate_thickness.h (1)) gives t_h(r) = k / sqrt(r^2 - c^2),
// k = K B t / pi, for a layer of K circuits of bands B wide and t thick turning around at r = c:
// infinite at r = c, though the fibre volume it lays is finite. Over the two band widths next to
// the turnaround, c <= r <= r_b = c + 2B, the thickness is the cubic
//   t(r) = a0 + a2 x^2 + a3 x^3,   x = r - c,
// flat at the turnaround (t'(c) = 0: the band's build-up peak) and chosen so that
//   t(r_b) = t_h(r_b),  t'(r_b) = t_h'(r_b)   (a smooth join with continuity), and
//   integral of t 2 pi r ds over the region = integral of t_h 2 pi r ds over it
// (the band volume laid there, finite: integral of r ds / sqrt(r^2 - c^2), exact per segment
// of the polyline, r linear in s). Each end of the meridian (each dome) gets its own cubic over
// its own region (the run of meridian from that end up to r_b); inside the turnaround (r < c) the
// layer is 0, beyond r_b it is t_h. Units: mm.
#include "planner/layup/laminate_thickness.h"

namespace windplan {

/// The layer's thickness at every point of `meridian` (header comment).
/// \throw InputError for invalid figures, or when r_b = c + 2 band_width is not below the
///        meridian's largest radius (no dome region to model: use fibre continuity).
LayerThickness helical_layer_thickness_spline(const MeridianPolyline& meridian, double c,
                                              double circuits, double band_width,
                                              double band_thickness);

/// The volume integral of t 2 pi r ds of `thickness` over the meridian between arc lengths s0 and
/// s1 (trapezoids on its points, t and r linear between them; mm^3).
double layer_volume(const MeridianPolyline& meridian, const LayerThickness& thickness, double s0,
                    double s1);

}  // namespace windplan
