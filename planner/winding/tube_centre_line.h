#pragma once
// Tube coordinates on a circular tube swept along a centre line of straight pieces and circular
// bends (the parametric bent tube / elbow of geometry/cad/parametric_mandrel.h, built here from
// the same numbers so that planner/ need not use geometry/cad).
//
// Coordinates: s the centre-line arc length from the tube's start (mm), theta the angle around
// the section (rad) measured in a rotation-minimising (Bishop) frame (t, u, v): u starts as +X,
// the start direction t as +Z, and both are carried through each bend by the bend's rotation (on
// a planar circular arc that is parallel transport, so the frame does not twist). The surface is
//   P(s, theta) = C(s) + r (cos theta u(s) + sin theta v(s)),   outward normal n = (P - C) / r.
// In a bend of radius R (curvature kappa = 1 / R) whose centre lies in the direction at angle
// `toward` in (u, v): P_s = h t with the stretch h = 1 - kappa r cos(theta - toward) (1 on a
// straight piece), P_theta = r (-sin theta u + cos theta v). The coordinates are orthogonal lines
// of curvature (metric h^2 ds^2 + r^2 dtheta^2), so for a curve at angle a from the centre-line
// direction t (towards +theta), Liouville's formula gives (k_g > 0 towards t x n, the side a
// grows to)
//   k_g = da/dl - h_theta cos(a) / (h r),   h_theta = kappa r sin(theta - toward),
// and Euler's (principal curvatures -kappa cos(theta - toward) / h along t, 1 / r around)
//   k_n = -kappa cos(theta - toward) cos^2(a) / h + sin^2(a) / r.
// On a torus (theta' = theta - toward - pi from the outside of the bend) a geodesic keeps
// (R + r cos theta') cos a constant (Clairaut), and holding a constant a needs
//   lambda = |k_g / k_n| = r sin(theta') cos(a) / ((R + r cos theta') sin^2(a) + r cos^2(a)
//   cos(theta')).
// Units: mm, radians.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "planner/winding/tube_surface.h"

namespace windplan {

/// One bend, as BendParams (geometry/cad/parametric_mandrel.h) gives it.
struct TubeBend {
  double angle_deg = 90.0;       ///< turn of the centre line (deg, in (0, 180])
  double radius = 100.0;         ///< centre-line bend radius (mm, > tube radius)
  double plane_angle_deg = 0.0;  ///< rotation of the bend plane about the incoming piece (deg)
};

/// The frame of the centre line at one station.
struct TubeFrame {
  Vec3 c = Vec3::Zero();   ///< centre-line point (mm)
  Vec3 t = Vec3::UnitZ();  ///< unit tangent
  Vec3 u = Vec3::UnitX();  ///< Bishop frame, theta = 0
  Vec3 v = Vec3::UnitY();  ///< t x u, theta = pi / 2
  double kappa = 0.0;      ///< centre-line curvature (1/mm; 0 on straight pieces)
  double toward = 0.0;     ///< angle (rad) in (u, v) of the direction to the bend centre
};

class TubeCentreLine : public TubeSurface {
 public:
  /// The centre line of parametric_mandrel's bent tube: segments[i] straight (mm, >= 0), then
  /// bends[i]; bends.size() == segments.size() - 1.
  /// \throw InputError for a radius <= 0, a bend radius <= the tube radius or a size mismatch
  TubeCentreLine(double tube_radius, const std::vector<double>& segments,
                 const std::vector<TubeBend>& bends);
  double length() const override { return length_; }
  double tube_radius() const { return r_; }
  /// The frame at s (beyond [0, length()] the end pieces continue straight).
  TubeFrame frame(double s) const;
  /// Surface point and unit outward normal at (s, theta).
  Vec3 point(double s, double theta) const override;
  Vec3 normal(double s, double theta) const override;
  /// Stretch h and its theta derivative at (s, theta) (see the header comment).
  double stretch(double s, double theta) const;
  double stretch_theta(double s, double theta) const;
  /// k_n of the direction at angle a from t at (s, theta) (1/mm, > 0 where the fibre presses on).
  double normal_curvature(double s, double theta, double a) const;
  /// The geodesic term of k_g: k_g = da/dl - geodesic_turn (1/mm).
  double geodesic_turn(double s, double theta, double a) const;
  /// The centre line as a polyline: its start, each straight piece's end, and per_bend points
  /// along each bend (at k / per_bend of its turn, k = 1..per_bend). The same points, to the bit,
  /// as geometry/cad/parametric_mandrel.h's bent_tube_centreline (the same arithmetic), so that
  /// the wound region's Spine (planner/mandrel/tube_spine.h) and the closed forms here are one
  /// centre line. \param per_bend >= 1
  std::vector<Vec3> polyline(int per_bend) const;
  /// Nearest centre-line station of p (mm, clamped to [0, length()]), its theta and the distance
  /// of p from that centre-line point (mm).
  void locate(const Vec3& p, double* s, double* theta, double* distance) const override;
  /// [s0, s1) of each bend (mm) with its curvature.
  struct BendSpan {
    double s0 = 0.0, s1 = 0.0, kappa = 0.0, toward = 0.0;
  };
  const std::vector<BendSpan>& bends() const { return spans_; }
  /// The bend holding s (nullptr: a straight piece).
  const BendSpan* bend_at(double s) const;
  /// The same figures with the piece given (nullptr: straight), so that an integrator can keep
  /// one piece's smooth formulas over a step that ends on a piece's end.
  double stretch(const BendSpan* b, double theta) const;
  double stretch_theta(const BendSpan* b, double theta) const;
  double normal_curvature(const BendSpan* b, double theta, double a) const;
  double geodesic_turn(const BendSpan* b, double theta, double a) const;
  /// TubeSurface: the pieces are the bends (index into bends(); -1 on a straight piece), their
  /// ends the bends' ends; rates from the closed forms (w = -geodesic_turn, e1 = t).
  int piece_at(double s) const override;
  std::vector<double> piece_ends() const override;
  Rates rates(int piece, double s, double theta, double a) const override;
  using TubeSurface::rates;
  double section_radius() const override { return r_; }
  /// constant_angle_demand (below).
  ConstantAngleDemand demand(double s0, double s1, double a) const override;

 private:
  struct Piece {
    bool bend = false;
    double s0 = 0.0, len = 0.0;
    TubeFrame f0;                                      // frame at the piece's start
    Vec3 centre = Vec3::Zero(), axis = Vec3::UnitZ();  // bend only
    double angle = 0.0;                                // bend only: its turn (rad)
  };
  int piece(double s) const;
  double r_ = 0.0, length_ = 0.0;
  std::vector<Piece> pieces_;
  std::vector<BendSpan> spans_;
};

/// |k_g / k_n| that holding the constant angle a from the centre line needs at (s, theta): the
/// geodesic term over k_n (infinite where k_n <= 0: the fibre would bridge).
double constant_angle_slippage(const TubeCentreLine& line, double s, double theta, double a);

/// The worst of constant_angle_slippage over the stations [s0, s1] and every theta (sampled at
/// 0.05 deg; within a bend it does not depend on s): the value, where (theta_outside from the
/// outside of the bend), and the least k_n.
ConstantAngleDemand constant_angle_demand(const TubeCentreLine& line, double s0, double s1,
                                          double a);

}  // namespace windplan
