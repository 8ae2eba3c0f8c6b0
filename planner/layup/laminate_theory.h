#pragma once
// The unidirectional ply of a wound laminate and classical laminate theory (CLT) for its
// membrane response.
//
// Ply from fibre and resin (rule of mixtures, V_f the fibre volume fraction, V_m = 1 - V_f):
//   E1   = E_f V_f + E_m V_m                       (fibres and resin side by side)
//   E2   = 1 / (V_f / E_f2 + V_m / E_m)            (in series across the fibres)
//   G12  = 1 / (V_f / G_f + V_m / G_m),  G_m = E_m / (2 (1 + nu_m))
//   nu12 = nu_f V_f + nu_m V_m
//   nu23 = nu_m (the plane across the fibres, resin dominated), G23 = E2 / (2 (1 + nu23)).
// Engineering constants given directly replace these (ElasticConstants).
//
// CLT. A ply at the angle a (from the meridian, the laminate's x axis; y the hoop direction) has
// the plane-stress stiffness Q (E1, E2, nu12, G12) rotated into (x, y): Qbar(a). A laminate of
// plies (a_k, t_k) has the membrane stiffness A = sum Qbar(a_k) t_k, and under the stress
// resultants N = (N_x, N_y, N_xy) (N/mm) with no curvature (a long cylinder) the mid-surface
// strains are eps = A^-1 N (eps_x, eps_y, gamma_xy engineering). A ply's strains along and across
// its fibres: eps_1 = eps_x c^2 + eps_y s^2 + gamma_xy s c, eps_2 = eps_x s^2 + eps_y c^2 -
// gamma_xy s c, gamma_12 = 2 (eps_y - eps_x) s c + gamma_xy (c^2 - s^2), c = cos a, s = sin a.
// Units: MPa, mm, degrees.
#include <array>
#include <string>
#include <vector>

namespace windplan {

/// Orthotropic engineering constants of a unidirectional ply (1 along the fibres).
struct ElasticConstants {
  double e1 = 0.0, e2 = 0.0, e3 = 0.0;        ///< MPa
  double nu12 = 0.0, nu13 = 0.0, nu23 = 0.0;  ///< dimensionless
  double g12 = 0.0, g13 = 0.0, g23 = 0.0;     ///< MPa
  bool is_valid(std::string* why) const;
};

/// The fibre and the resin a ply is made of.
struct FibreResin {
  double fibre_modulus = 230000.0;            ///< E_f along the fibre (MPa); T700S
  double fibre_transverse_modulus = 15000.0;  ///< E_f2 across the fibre (MPa)
  double fibre_shear_modulus = 15000.0;       ///< G_f (MPa)
  double fibre_poisson = 0.2;                 ///< nu_f
  double resin_modulus = 3500.0;              ///< E_m (MPa); epoxy
  double resin_poisson = 0.35;                ///< nu_m
  double volume_fraction = 0.6;               ///< V_f, (0, 1)
  bool is_valid(std::string* why) const;
};

/// The ply's constants by the rule of mixtures (header comment). \throw ConfigError if invalid.
ElasticConstants rule_of_mixtures(const FibreResin& m);

using Vec3d = std::array<double, 3>;
using Mat3d = std::array<std::array<double, 3>, 3>;

/// One ply of a laminate.
struct Ply {
  double angle_deg = 0.0;  ///< fibre angle from the laminate's x axis (the meridian)
  double thickness = 0.0;  ///< mm
};

/// The reduced plane-stress stiffness Q of the ply rotated by angle_deg (Qbar, MPa), acting on
/// (eps_x, eps_y, gamma_xy).
Mat3d rotated_stiffness(const ElasticConstants& c, double angle_deg);

/// A = sum Qbar(a_k) t_k (N/mm).
Mat3d membrane_stiffness(const ElasticConstants& c, const std::vector<Ply>& plies);

/// eps = A^-1 N (header comment). \throw InputError when A is singular.
Vec3d membrane_strains(const ElasticConstants& c, const std::vector<Ply>& plies, const Vec3d& n);

/// (eps_1, eps_2, gamma_12) of a ply at angle_deg under the laminate strains eps.
Vec3d ply_strains(const Vec3d& eps, double angle_deg);

/// (sigma_1, sigma_2, tau_12) of the ply from its own strains (MPa).
Vec3d ply_stresses(const ElasticConstants& c, const Vec3d& eps12);

}  // namespace windplan
