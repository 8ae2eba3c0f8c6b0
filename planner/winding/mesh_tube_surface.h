#pragma once
// A smooth tube surface (planner/winding/tube_surface.h) fitted to a tube-shaped mesh around its
// centre line (geometry/region/spine.h): what friction layers run on where no closed form exists
// (mesh and CAD tubes, oval and rounded-rectangle sections).
//
//   P(s, theta) = C(s) + rho(s, theta) (cos theta u(s) + sin theta v(s)),
// s the station (mm from the spine's start), (u, v) a rotation-minimising frame normal to the
// centre line C (double reflection, Wang et al. 2008, "Computation of rotation minimizing
// frames"). Built on nodes every `step` mm:
//  - C: at each node a local linear least-squares fit (tricube weights, half-width `window`)
//    of the spine's points against their arc length: inside, a positive-kernel average, so the
//    section centroids' tessellation noise is smoothed, a circular bend keeps its curvature
//    (the smoothed line runs about 0.07 kappa window^2 inside it, concentric) and a bend's end
//    becomes a ramp of curvature without overshoot (a local quadratic overshoots it by ~5%);
//  - rho: the section of the mesh by the plane normal to C' at each node (PlaneSectioner's loop
//    around the tube), cut by `rays` rays from C in the plane, as a truncated Fourier series in
//    theta (`harmonics` terms), its coefficients smoothed along s by the same local fit;
//    where that series makes a section concave (flat sides), the series of 1 / rho smoothed by
//    a positive kernel instead (convex_width), which keeps convex sections convex;
//  - C, u, v and the coefficients are clamped cubic splines in s, so P is C2 and every
//    derivative the rates need (P_s, P_theta, P_ss, P_stheta, P_thetatheta) is analytic. Beyond
//    [0, length] the ends continue straight with their end sections.
// One smooth piece: no piece ends. Units: mm, radians.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "geometry/region/spine.h"
#include "planner/winding/tube_surface.h"

namespace windplan {

struct MeshTubeSurfaceOptions {
  double step = std::nan("");  ///< node spacing (mm, > 0; NaN: a quarter of the mean radius)
  /// Half-width of the smoothing fit along s (mm; NaN: 0.75 x the mean radius, at least 2.5
  /// steps; wider smooths more noise but spreads a bend's end: at 1.5 x the radius a 3r elbow's
  /// constant-angle demand measures 3.5% above its closed form, at 0.75 x 1.7%).
  double window = std::nan("");
  int harmonics = 16;  ///< Fourier terms of rho in theta (count, 1..64)
  int rays = 256;      ///< rays per section (count, >= 4 x harmonics)
  /// Where the series of rho would make a section concave somewhere (a rounded rectangle's flat
  /// sides: its truncated series ripples there), the section is fitted instead by the series of
  /// u = 1 / rho smoothed by a wrapped Gaussian of this width in theta (rad, 0.03..1): a
  /// positive kernel, so the fitted section's curvature (sign of u + u'') is >= 0 wherever the
  /// mesh section is convex, ~0 on its flats beyond ~3 widths of a corner; 6.5 / width terms
  /// (the kernel's series to 1e-9), from 4 rays per term. Narrow enough that a turnaround turns
  /// only where the mesh is curved within a measuring window (a band width) of it.
  double convex_width = 0.04;
  bool is_valid(std::string* why) const;
};

struct MeshTubeSurfaceSummary {
  int sections = 0;              ///< sections cut (nodes)
  double step = 0.0;             ///< mm used
  double window = 0.0;           ///< mm used
  double mean_radius = 0.0;      ///< mean rho (mm)
  double fit_residual = 0.0;     ///< largest |fitted rho - ray| over every ray of every node (mm)
  int harmonics = 0;             ///< Fourier terms kept (those that change k_n by > 1e-5)
  int non_star_rays = 0;         ///< rays that met their section more than once (largest taken)
  bool convex_fit = false;       ///< sections fitted by the smoothed series of 1 / rho
  double least_curvature = 0.0;  ///< least section curvature x mean radius of the rho series (1)
  std::string brief_report() const;
};

struct MeshTubeSurfaceResult;

class MeshTubeSurface : public TubeSurface {
 public:
  double length() const override { return length_; }
  Vec3 point(double s, double theta) const override;
  Vec3 normal(double s, double theta) const override;
  int piece_at(double) const override { return -1; }
  std::vector<double> piece_ends() const override { return {}; }
  Rates rates(int piece, double s, double theta, double a) const override;
  using TubeSurface::rates;
  void locate(const Vec3& p, double* s, double* theta, double* distance) const override;
  double section_radius() const override { return section_radius_; }
  /// From the section's length at 720 angles (linear between them, both ways).
  double even_angle(double s, double theta) const override;
  double from_even_angle(double s, double psi) const override;
  bool even_is_theta() const override { return false; }
  /// TubeSurface::demand with theta_outside from the outside of the bend (opposite C'').
  ConstantAngleDemand demand(double s0, double s1, double a) const override;
  /// The centre-line point and its first two derivatives in s.
  void centre(double s, Vec3* c, Vec3* c1, Vec3* c2) const;
  /// The section's girth at s (mm, from the fit, 720 samples).
  double girth(double s) const;

 private:
  friend MeshTubeSurfaceResult mesh_tube_surface(const Mesh&, const Spine&, const SpindleAxis&,
                                                 const MeshTubeSurfaceOptions&);
  struct Eval;
  Eval eval(double s, double theta) const;
  void build_polynomials();
  // Built by mesh_tube_surface: node spacing, channels per node (C, u, v, the Fourier
  // coefficients a0, a1, b1, ...), their spline second derivatives.
  double h_ = 1.0, length_ = 0.0, section_radius_ = 0.0;
  int harmonics_ = 0;
  bool inverse_ = false;  ///< the series is u = 1 / rho's (the convex fit)
  std::vector<std::vector<double>> y_, m_;
  std::vector<double> poly_;     ///< per interval and channel, the cubic's coefficients
  std::size_t poly_stride_ = 0;  ///< doubles per interval
  Spine nodes_;                  ///< the nodes' centre points, for locate's first guess
};

struct MeshTubeSurfaceResult {
  std::shared_ptr<const MeshTubeSurface> surface;
  MeshTubeSurfaceSummary summary;
};

/// The fit of the annulus `mesh` around `spine` (see the header comment).
/// \param axis only to tell which section loop goes around the tube (PlaneSectioner)
/// \throw InputError naming the station where a section normal to the centre line does not go
///        around the tube or a ray from the centre misses it; ConfigError for invalid options.
MeshTubeSurfaceResult mesh_tube_surface(const Mesh& mesh, const Spine& spine,
                                        const SpindleAxis& axis,
                                        const MeshTubeSurfaceOptions& options = {});

}  // namespace windplan
