#include "planner/layup/laminate_theory.h"

#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

namespace {

bool positive(double v) { return v > 0.0 && std::isfinite(v); }

bool fail(std::string* why, const std::string& m) {
  if (why) *why = m;
  return false;
}

}  // namespace

bool ElasticConstants::is_valid(std::string* why) const {
  for (double v : {e1, e2, e3, g12, g13, g23}) {
    if (!positive(v))
      return fail(why, "moduli must be > 0 MPa (got " + format_number("%g", v) + ")");
  }
  for (double v : {nu12, nu13, nu23}) {
    if (!(v > -1.0 && v < 0.5 + 1e-12)) {
      return fail(why, "Poisson ratios must be in (-1, 0.5] (got " + format_number("%g", v) + ")");
    }
  }
  if (!(nu12 * nu12 * e2 / e1 < 1.0)) return fail(why, "nu12^2 E2 / E1 must be < 1");
  return true;
}

bool FibreResin::is_valid(std::string* why) const {
  const std::pair<const char*, double> moduli[] = {
      {"fibre_modulus", fibre_modulus},
      {"fibre_transverse_modulus", fibre_transverse_modulus},
      {"fibre_shear_modulus", fibre_shear_modulus},
      {"resin_modulus", resin_modulus}};
  for (const auto& [k, v] : moduli) {
    if (!positive(v)) {
      return fail(why, std::string(k) + " must be > 0 MPa (got " + format_number("%g", v) + ")");
    }
  }
  if (!(fibre_poisson > -1.0 && fibre_poisson < 0.5)) {
    return fail(
        why, "fibre_poisson must be in (-1, 0.5) (got " + format_number("%g", fibre_poisson) + ")");
  }
  if (!(resin_poisson > -1.0 && resin_poisson < 0.5)) {
    return fail(
        why, "resin_poisson must be in (-1, 0.5) (got " + format_number("%g", resin_poisson) + ")");
  }
  if (!(volume_fraction > 0.0 && volume_fraction < 1.0)) {
    return fail(why, "fibre_volume_fraction must be in (0, 1) (got " +
                         format_number("%g", volume_fraction) + ")");
  }
  return true;
}

ElasticConstants rule_of_mixtures(const FibreResin& m) {
  std::string why;
  if (!m.is_valid(&why)) throw ConfigError("design: " + why);
  const double vf = m.volume_fraction, vm = 1.0 - vf;
  const double gm = m.resin_modulus / (2.0 * (1.0 + m.resin_poisson));
  ElasticConstants c;
  c.e1 = m.fibre_modulus * vf + m.resin_modulus * vm;
  c.e2 = 1.0 / (vf / m.fibre_transverse_modulus + vm / m.resin_modulus);
  c.e3 = c.e2;
  c.g12 = 1.0 / (vf / m.fibre_shear_modulus + vm / gm);
  c.g13 = c.g12;
  c.nu12 = m.fibre_poisson * vf + m.resin_poisson * vm;
  c.nu13 = c.nu12;
  c.nu23 = m.resin_poisson;
  c.g23 = c.e2 / (2.0 * (1.0 + c.nu23));
  return c;
}

Mat3d rotated_stiffness(const ElasticConstants& k, double angle_deg) {
  const double nu21 = k.nu12 * k.e2 / k.e1, d = 1.0 - k.nu12 * nu21;
  const double q11 = k.e1 / d, q22 = k.e2 / d, q12 = k.nu12 * k.e2 / d, q66 = k.g12;
  const double a = angle_deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  const double c2 = c * c, s2 = s * s, cs = c * s;
  Mat3d q{};
  q[0][0] = q11 * c2 * c2 + 2.0 * (q12 + 2.0 * q66) * s2 * c2 + q22 * s2 * s2;
  q[1][1] = q11 * s2 * s2 + 2.0 * (q12 + 2.0 * q66) * s2 * c2 + q22 * c2 * c2;
  q[0][1] = q[1][0] = (q11 + q22 - 4.0 * q66) * s2 * c2 + q12 * (s2 * s2 + c2 * c2);
  q[2][2] = (q11 + q22 - 2.0 * q12 - 2.0 * q66) * s2 * c2 + q66 * (s2 * s2 + c2 * c2);
  q[0][2] = q[2][0] = (q11 - q12 - 2.0 * q66) * c2 * cs + (q12 - q22 + 2.0 * q66) * s2 * cs;
  q[1][2] = q[2][1] = (q11 - q12 - 2.0 * q66) * s2 * cs + (q12 - q22 + 2.0 * q66) * c2 * cs;
  return q;
}

Mat3d membrane_stiffness(const ElasticConstants& c, const std::vector<Ply>& plies) {
  Mat3d a{};
  for (const Ply& p : plies) {
    const Mat3d q = rotated_stiffness(c, p.angle_deg);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a[i][j] += q[i][j] * p.thickness;
  }
  return a;
}

Vec3d membrane_strains(const ElasticConstants& c, const std::vector<Ply>& plies, const Vec3d& n) {
  const Mat3d a = membrane_stiffness(c, plies);
  auto det3 = [](const Mat3d& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det3(a);
  if (!(std::abs(d) > 0.0) || !std::isfinite(d)) {
    throw InputError("laminate theory: the membrane stiffness is singular (no plies?)");
  }
  Vec3d e{};
  for (int k = 0; k < 3; ++k) {  // Cramer's rule
    Mat3d m = a;
    for (int i = 0; i < 3; ++i) m[i][k] = n[i];
    e[k] = det3(m) / d;
  }
  return e;
}

Vec3d ply_strains(const Vec3d& e, double angle_deg) {
  const double a = angle_deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  return {e[0] * c * c + e[1] * s * s + e[2] * s * c, e[0] * s * s + e[1] * c * c - e[2] * s * c,
          2.0 * (e[1] - e[0]) * s * c + e[2] * (c * c - s * s)};
}

Vec3d ply_stresses(const ElasticConstants& k, const Vec3d& e) {
  const double nu21 = k.nu12 * k.e2 / k.e1, d = 1.0 - k.nu12 * nu21;
  return {(k.e1 * e[0] + k.nu12 * k.e2 * e[1]) / d, (k.nu12 * k.e2 * e[0] + k.e2 * e[1]) / d,
          k.g12 * e[2]};
}

}  // namespace windplan
