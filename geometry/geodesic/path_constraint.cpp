#include "geometry/geodesic/path_constraint.h"

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

void tangent_basis(const Vec3& n, Vec3* t1, Vec3* t2) {
  const Vec3 a = std::fabs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  *t1 = n.cross(a).normalized();
  *t2 = n.cross(*t1);
}

}  // namespace

PlaneConstraint::PlaneConstraint(const Vec3& normal, double offset, Mode mode, double max_tilt_rad)
    : mode_(mode), d0_(offset), max_tilt_(max_tilt_rad) {
  const double len = normal.norm();
  if (!(len > 0.0) || !std::isfinite(len) || !std::isfinite(offset)) {
    throw InputError("plane constraint: the normal must be a finite non-zero vector");
  }
  n0_ = normal / len;
  initial_n_ = n0_;
  tangent_basis(n0_, &t1_, &t2_);
}

int PlaneConstraint::num_variables() const {
  switch (mode_) {
    case Mode::Fixed:
      return 0;
    case Mode::FixedNormal:
      return 1;
    case Mode::Free:
      return 3;
  }
  return 0;
}

void PlaneConstraint::initial_variables(double* z) const {
  if (mode_ == Mode::FixedNormal) z[0] = d0_;
  if (mode_ == Mode::Free) {
    z[0] = 0.0;
    z[1] = 0.0;
    z[2] = d0_;
  }
}

Vec3 PlaneConstraint::normal(const double* z) const {
  if (mode_ != Mode::Free) return n0_;
  return (n0_ + z[0] * t1_ + z[1] * t2_).normalized();
}

double PlaneConstraint::offset(const double* z) const {
  switch (mode_) {
    case Mode::Fixed:
      return d0_;
    case Mode::FixedNormal:
      return z[0];
    case Mode::Free:
      return z[2];
  }
  return d0_;
}

double PlaneConstraint::evaluate(const Vec3& p, const double* z, Vec3* dr_dp, double* dr_dz) const {
  if (mode_ != Mode::Free) {
    *dr_dp = n0_;
    if (mode_ == Mode::FixedNormal) dr_dz[0] = -1.0;
    return n0_.dot(p) - offset(z);
  }
  const Vec3 m = n0_ + z[0] * t1_ + z[1] * t2_;
  const double len = m.norm();
  const Vec3 n = m / len;
  *dr_dp = n;
  // dn/du_a = (I - n n^T) t_a / |m|
  const Vec3 q = (p - n * n.dot(p)) / len;
  dr_dz[0] = q.dot(t1_);
  dr_dz[1] = q.dot(t2_);
  dr_dz[2] = -1.0;
  return n.dot(p) - z[2];
}

void PlaneConstraint::recentre(double* z) {
  if (mode_ != Mode::Free) return;
  Vec3 n = normal(z);
  // Keep the normal within the cone around the initial normal.
  if (max_tilt_ < M_PI / 2) {
    const double c = std::clamp(n.dot(initial_n_), -1.0, 1.0);
    const double ang = std::acos(c);
    if (ang > max_tilt_) {
      const Vec3 perp = (n - c * initial_n_).normalized();
      n = std::cos(max_tilt_) * initial_n_ + std::sin(max_tilt_) * perp;
    }
  }
  n0_ = n;
  tangent_basis(n0_, &t1_, &t2_);
  z[0] = 0.0;
  z[1] = 0.0;
}

}  // namespace windplan
