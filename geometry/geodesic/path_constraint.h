#pragma once
// Penalty constraints for the geodesic core (Liu et al., the penalty M*H^2 after eq. 2, and the
// coplanar constraint of eq. 7/8).
//
// A PathConstraint is a residual r(p, z) = 0 required at every point p of the path (crossings and,
// for open paths, both endpoints), possibly depending on m extra variables z optimised together
// with the path (e.g. a free plane). The solver adds sum_q (mu_q r_q + M/2 r_q^2) (augmented
// Lagrangian; mu = 0 gives the paper's plain penalty) and uses the Gauss-Newton Hessian.
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

class PathConstraint {
 public:
  virtual ~PathConstraint() = default;
  /// Number m of extra variables z (0 for a constraint on the path alone).
  virtual int num_variables() const = 0;
  /// Writes the initial z (m values).
  virtual void initial_variables(double* z) const = 0;
  /// r(p, z); writes dr/dp and dr/dz (m values; may be null when m == 0).
  virtual double evaluate(const Vec3& p, const double* z, Vec3* dr_dp, double* dr_dz) const = 0;
  /// Between outer iterations: re-centre a local parametrisation, project onto limits. May change
  /// z (and must keep r unchanged for an unchanged geometric state).
  virtual void recentre(double* /*z*/) {}
};

/// Coplanarity n . p - d = 0 (eq. 7/8). The plane is fixed, or its offset only is free, or it
/// is entirely free (normal and offset), optionally with the normal kept within a cone around
/// the initial normal.
class PlaneConstraint : public PathConstraint {
 public:
  enum class Mode {
    Fixed,        ///< n and d fixed
    FixedNormal,  ///< n fixed, d free (the plane may only translate)
    Free,         ///< n and d free
  };
  /// \param normal initial unit normal (normalised here), \param offset initial d (mm),
  /// \param max_tilt_rad in Free mode, the largest angle between n and the initial normal
  ///        (pi/2 or more: unlimited)
  PlaneConstraint(const Vec3& normal, double offset, Mode mode, double max_tilt_rad = M_PI);

  int num_variables() const override;
  void initial_variables(double* z) const override;
  double evaluate(const Vec3& p, const double* z, Vec3* dr_dp, double* dr_dz) const override;
  void recentre(double* z) override;

  /// The plane for variables z: unit normal and offset.
  Vec3 normal(const double* z) const;
  double offset(const double* z) const;

 private:
  Mode mode_;
  Vec3 n0_, initial_n_;  // current centre of the normal's parametrisation, and the initial normal
  Vec3 t1_, t2_;         // tangent basis at n0_
  double d0_;
  double max_tilt_;
};

}  // namespace windplan
