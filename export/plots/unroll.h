#pragma once
// The coordinates a development plot unrolls the wound surface into: "along" (mm, between the two
// ends) and "around" (deg, in [0, 360)).
//
// Shapes of revolution (the caller says so, or PlanMetrics::geodesic_turn_limit is a number) and
// any mesh that is not an annulus: along
// is the axial position about the spindle axis, around the angle of export/machine/kinematics.h's
// AxisFrame (counter-clockwise about the axis direction).
// Other annuli (a bent tube): the wound region's own conformal coordinates
// (planner/winding/harmonic.h): along = h * L with h the harmonic height (0 on the boundary loop at
// the lower axial position, the winding surface's start loop, 1 on the other;
// planner/winding/coverage.h's levels are this h) and L = area / mean perimeter of the two loops
// (the length of a tube of constant section), around = the conjugate angle theta. So a bent tube
// unrolls like a straight one: a helix about its centre line is a straight band, instead of loops
// about a principal axis. A point is located by its mesh face when given and on it, else near the
// last point located, else by the closest face of all; h and the lifted angle are interpolated
// inside that face.
#include <optional>
#include <string>
#include <vector>

#include "export/machine/kinematics.h"
#include "geometry/mesh/mesh.h"
#include "planner/plan/plan.h"
#include "planner/winding/harmonic.h"

namespace windplan {

class Unrolling {
 public:
  enum class Kind { Axis, Conformal };

  /// Chooses the kind as described above (the conformal one needs an annulus mesh; without it, or
  /// when the harmonic solve throws, the axis one with `fallback_reason` set).
  /// `face_map` (optional): per face of `mandrel`, the face of the mesh that FibrePoint::face
  /// indexes (WindingSurface::face_map when `mandrel` is the wound region cut out of the full
  /// mesh).
  /// `revolution` (optional): whether the mandrel is a shape of revolution (Mandrel::revolution);
  /// unset: PlanMetrics::geodesic_turn_limit is a number.
  static Unrolling make(const WindingPlan& plan, const Mesh& mandrel,
                        const std::vector<int>* face_map = nullptr,
                        std::optional<bool> revolution = std::nullopt);

  Kind kind() const { return kind_; }
  /// (along mm, around deg in [0, 360)) of a point on (or near) the mandrel; `face` a hint (-1:
  /// none).
  Vec2 map(const Vec3& p, int face = -1) const;
  /// The map of q, a point near `anchor` off the surface (a band edge in the tangent plane):
  /// the conformal kind extends the linear map of the anchor's face to q (first order), the axis
  /// kind maps q itself.
  Vec2 map_offset(const Vec3& anchor, int face, const Vec3& q) const;
  /// Length L of the conformal kind (mm); 0 for the axis kind.
  double length() const { return length_; }
  std::string along_title() const;
  std::string around_title() const;
  std::string fallback_reason;  ///< why the conformal kind was not used (empty: not tried / used)

 private:
  Kind kind_ = Kind::Axis;
  AxisFrame frame_;
  Mesh mesh_;                   ///< a copy (conformal kind only)
  mutable int last_face_ = -1;  ///< the face of the last point located (a search hint; not
                                ///< thread-safe: one Unrolling per thread)
  std::vector<int> hint_face_;  ///< FibrePoint::face -> face of mesh_ (-1: none); empty: identity
  HarmonicCoordinates hc_;
  double length_ = 0.0;
  bool barycentric(const Vec3& p, int f, Vec3* bary) const;
  double face_distance(const Vec3& p, int f, Vec3* bary) const;
  int locate(const Vec3& p, int face, Vec3* bary) const;
  Vec2 eval(int f, const Vec3& bary) const;
};

}  // namespace windplan
