#pragma once
// A tube surface in tube coordinates, the one the friction planner
// (planner/winding/tube_friction.h) runs on: s the station along the centre line (mm, [0,
// length()]), theta the angle around the section (rad). Two implementations: a parametric bent
// tube's exact circular tube with closed forms (planner/winding/tube_centre_line.h) and a smooth
// fit of any tube-shaped mesh around its centre line (planner/winding/mesh_tube_surface.h: meshes,
// CAD, oval sections).
//
// Convention. P(s, theta) is the surface point, n its unit outward normal, e1 = P_s / |P_s| the
// direction along the tube, e2 = e1 x n the unit tangent across it, towards +theta. A fibre at
// angle a from e1 (towards e2) has the unit tangent T = cos a e1 + sin a e2; along it (l the
// fibre length, mm)
//   ds/dl, dtheta/dl  from P_s ds + P_theta dtheta = T dl,
//   k_n = -(dT/dl) . n          (1/mm, > 0 where the fibre presses on the surface),
//   k_g = da/dl + w,  w = (de1/dl) . e2   (the geodesic term; T' . (n x T) = a' + e1' . e2 since
//                                          e1' . e1 = e2' . e2 = 0 and e2' . e1 = -e1' . e2).
// A constant angle a needs friction |k_g / k_n| = |w| / k_n; a friction turnaround at |k_g/k_n| =
// lambda on side sigma runs da/dl = -w + sigma lambda k_n.
// Pieces: the rates may be smooth only within pieces (a bent tube's bends and straights); an
// integrator keeps one piece's formulas over a step and cuts steps at piece_ends().
// Units: mm, radians.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

/// Curvature below which a direction counts as straight (1/mm, a radius of 10 km): where k_n
/// and the geodesic term are both below it in size the fibre runs straight on a flat side.
constexpr double kFlatCurvature = 1e-7;

/// The worst |k_g / k_n| a constant angle needs over some stations: the value, where, and the
/// least k_n.
struct ConstantAngleDemand {
  double slippage = 0.0;       ///< max |k_g / k_n| (inf where k_n <= 0 somewhere)
  double s = 0.0;              ///< station of the worst (mm)
  double theta_outside = 0.0;  ///< its angle (rad, in (-pi, pi]; on a bend from the outside)
  double min_k_n = 0.0;        ///< least k_n over the region (1/mm)
};

class TubeSurface {
 public:
  /// What a fibre at angle a sees at (s, theta) (see the header comment).
  struct Rates {
    double ds = 0.0;   ///< ds/dl (1)
    double dth = 0.0;  ///< dtheta/dl (rad/mm)
    double k_n = 0.0;  ///< normal curvature of the direction (1/mm)
    double w = 0.0;    ///< geodesic term: k_g = da/dl + w (1/mm)
  };
  virtual ~TubeSurface() = default;
  /// Stations [0, length()] (mm).
  virtual double length() const = 0;
  virtual Vec3 point(double s, double theta) const = 0;
  /// Unit outward normal.
  virtual Vec3 normal(double s, double theta) const = 0;
  /// The piece holding s (an index for rates(); -1 where the surface has one smooth piece there).
  virtual int piece_at(double s) const = 0;
  /// The stations where pieces meet (an integrator cuts its steps there).
  virtual std::vector<double> piece_ends() const = 0;
  /// The rates with the piece's formulas (smooth a little beyond its ends).
  virtual Rates rates(int piece, double s, double theta, double a) const = 0;
  Rates rates(double s, double theta, double a) const { return rates(piece_at(s), s, theta, a); }
  /// Nearest station of p (clamped to [0, length()]), its theta, and the distance of p from the
  /// centre-line point there (mm).
  virtual void locate(const Vec3& p, double* s, double* theta, double* distance) const = 0;
  /// The largest section's girth / (2 pi) (mm): sets the default circuit count and first guesses.
  virtual double section_radius() const = 0;
  /// The even angle at s: 2 pi times the fraction of the section loop's length from theta = 0
  /// to theta (unwrapped with theta: +2 pi per turn), so that angles spread evenly in it lie
  /// evenly along the loop. theta itself on a circular section (the default).
  virtual double even_angle(double, double theta) const { return theta; }
  /// True where even_angle is theta itself (circular sections).
  virtual bool even_is_theta() const { return true; }
  /// Its inverse at s.
  virtual double from_even_angle(double, double psi) const { return psi; }
  /// max |w| / k_n at angle a over the stations [s0, s1] and every theta, with where (0 where
  /// both are below kFlatCurvature, inf where k_n <= 0 otherwise).
  virtual ConstantAngleDemand demand(double s0, double s1, double a) const;
};

}  // namespace windplan
