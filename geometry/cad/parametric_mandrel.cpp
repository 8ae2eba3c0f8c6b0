#include "geometry/cad/parametric_mandrel.h"

#include <algorithm>
#include <cmath>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepLib.hxx>
#include <BRepOffsetAPI_MakePipe.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Elips.hxx>
#include <gp_Pln.hxx>

#include "geometry/base/errors.h"
#include "geometry/base/param_check.h"
#include "geometry/cad/cad_shape_occt.h"

namespace windplan {

namespace {

using param_check::fail;
using param_check::num;
using param_check::positive;

template <class P>
void require_valid(const P& p, const char* what) {
  std::string why;
  if (!p.is_valid(&why)) throw ConfigError(std::string(what) + ": " + why);
}

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x(), v.y(), v.z()); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x(), v.y(), v.z()); }

// rho^2 - rho0^2 - (1 - rho0^2) rho^6: the isotensoid radicand (dimensionless).
double iso_radicand(double rho, double rho0) {
  const double r2 = rho * rho;
  return r2 - rho0 * rho0 - (1.0 - rho0 * rho0) * r2 * r2 * r2;
}

bool dome_valid(const DomeParams& d, double R, const std::string& key, std::string* why) {
  if (!positive(d.polar_opening)) {
    return fail(why, key + ".polar_opening must be > 0 mm (got " + num(d.polar_opening) + ")");
  }
  if (!(d.polar_opening < R)) {
    return fail(why, key + ".polar_opening (" + num(d.polar_opening) +
                         " mm) must be smaller than the vessel radius (" + num(R) + " mm)");
  }
  if (d.type == DomeType::Elliptical && !(positive(d.aspect) && d.aspect <= 10.0)) {
    return fail(
        why, key + ".aspect (dome height / radius) must be in (0, 10] (got " + num(d.aspect) + ")");
  }
  if (d.type == DomeType::Isotensoid && !(d.polar_opening / R < std::sqrt(2.0 / 3.0) - 1e-3)) {
    return fail(why, key + ".polar_opening / radius = " + num(d.polar_opening / R) +
                         ": an isotensoid dome needs a ratio below sqrt(2/3) = 0.816");
  }
  return true;
}

}  // namespace

const char* to_string(DomeType t) {
  switch (t) {
    case DomeType::Hemispherical:
      return "hemispherical";
    case DomeType::Elliptical:
      return "elliptical";
    case DomeType::Isotensoid:
      return "isotensoid";
  }
  return "hemispherical";
}

DomeType parse_dome_type(const std::string& s) {
  if (s == "hemispherical") return DomeType::Hemispherical;
  if (s == "elliptical") return DomeType::Elliptical;
  if (s == "isotensoid") return DomeType::Isotensoid;
  throw InputError("unknown dome type '" + s + "' (use hemispherical, elliptical or isotensoid)");
}

bool PipeParams::is_valid(std::string* why) const {
  if (!positive(radius)) return fail(why, "radius must be > 0 mm (got " + num(radius) + ")");
  if (!positive(length)) return fail(why, "length must be > 0 mm (got " + num(length) + ")");
  return true;
}

bool ConeParams::is_valid(std::string* why) const {
  if (!positive(radius_start)) {
    return fail(why, "radius_start must be > 0 mm (got " + num(radius_start) + ")");
  }
  if (!positive(radius_end)) {
    return fail(why, "radius_end must be > 0 mm (got " + num(radius_end) + ")");
  }
  if (!positive(length)) return fail(why, "length must be > 0 mm (got " + num(length) + ")");
  return true;
}

bool VesselParams::is_valid(std::string* why) const {
  if (!positive(radius)) return fail(why, "radius must be > 0 mm (got " + num(radius) + ")");
  if (!(std::isfinite(length) && length >= 0.0)) {
    return fail(why, "length must be >= 0 mm (got " + num(length) + ")");
  }
  if (isotensoid_samples < 8) return fail(why, "isotensoid_samples must be >= 8");
  return dome_valid(dome_start, radius, "dome_start", why) &&
         dome_valid(dome_end, radius, "dome_end", why);
}

bool BentTubeParams::is_valid(std::string* why) const {
  if (!positive(radius)) return fail(why, "radius must be > 0 mm (got " + num(radius) + ")");
  if (segments.empty()) return fail(why, "segments needs at least one straight length");
  if (bends.size() + 1 != segments.size()) {
    return fail(why, "bends must have one entry fewer than segments (" +
                         std::to_string(segments.size()) + " segments, " +
                         std::to_string(bends.size()) + " bends)");
  }
  double total = 0.0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (!(std::isfinite(segments[i]) && segments[i] >= 0.0)) {
      return fail(why, "segments[" + std::to_string(i) + "] must be >= 0 mm (got " +
                           num(segments[i]) + ")");
    }
    total += segments[i];
  }
  for (std::size_t i = 0; i < bends.size(); ++i) {
    const BendParams& b = bends[i];
    const std::string k = "bends[" + std::to_string(i) + "]";
    if (!(b.angle > 0.0 && b.angle <= 180.0)) {
      return fail(why, k + ".angle must be in (0, 180] degrees (got " + num(b.angle) + ")");
    }
    if (!(std::isfinite(b.radius) && b.radius > radius)) {
      return fail(why, k + ".radius (" + num(b.radius) +
                           " mm) must be larger than the tube radius (" + num(radius) + " mm)");
    }
    if (!std::isfinite(b.plane_angle)) return fail(why, k + ".plane_angle must be finite");
    total += b.radius * b.angle * M_PI / 180.0;
  }
  if (!(total > 0.0)) return fail(why, "the centreline has zero length");
  return true;
}

double isotensoid_neck_radius(double R, double r0) {
  const double rho0 = r0 / R;
  // The radicand rises from < 0 at rho0 to its maximum at rho_m = (3 (1 - rho0^2))^(-1/4).
  double lo = rho0, hi = std::pow(3.0 * (1.0 - rho0 * rho0), -0.25);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (iso_radicand(mid, rho0) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) * R;
}

double dome_opening_radius(const DomeParams& d, double R) {
  return d.type == DomeType::Isotensoid ? isotensoid_neck_radius(R, d.polar_opening)
                                        : d.polar_opening;
}

std::vector<Vec2> dome_meridian(const DomeParams& d, double R, int n) {
  n = std::max(n, 2);
  std::vector<Vec2> pts(n);
  if (d.type != DomeType::Isotensoid) {
    const double a = d.type == DomeType::Hemispherical ? 1.0 : d.aspect;
    const double u0 = std::acos(d.polar_opening / R);
    for (int i = 0; i < n; ++i) {
      const double u = u0 * i / (n - 1);
      pts[i] = Vec2(R * std::cos(u), a * R * std::sin(u));
    }
    pts.back().x() = d.polar_opening;
    return pts;
  }
  // Isotensoid: with r(t) = r1 + (R - r1) sin^2(t / 2) the height is a smooth integral in t.
  // The radicand f = rho^2 - rho0^2 - (1 - rho0^2) rho^6 vanishes at the neck rho1 and at the
  // equator rho = 1; factored there (using f(rho1) = 0, i.e. (1 - rho0^2)(1 + rho1^2 + rho1^4)
  // = 1), f = (1 - rho0^2)(rho - rho1)(rho + rho1)(1 - rho)(1 + rho)(1 + rho^2 + rho1^2), where
  // rho - rho1 = (1 - rho1) sin^2(t / 2) and 1 - rho = (1 - rho1) cos^2(t / 2) cancel against
  // dr / dt = (R - r1) sin(t / 2) cos(t / 2), leaving
  //   dz / dt = R rho^3 / sqrt((rho + rho1)(1 + rho)(1 + rho^2 + rho1^2)),
  // free of the end singularities and of cancellation (evaluating f itself lost all its digits
  // within 1e-8 of the neck: garbage heights from about 3e5 samples on). 4-point Gauss-Legendre
  // on sub-intervals of t.
  const double r1 = isotensoid_neck_radius(R, d.polar_opening);
  const double rho1 = r1 / R;
  auto integrand = [&](double t) {
    const double s = std::sin(0.5 * t);
    const double rho = rho1 + (1.0 - rho1) * s * s;
    return R * rho * rho * rho /
           std::sqrt((rho + rho1) * (1.0 + rho) * (1.0 + rho * rho + rho1 * rho1));
  };
  static const double gx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                               0.8611363115940526};
  static const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                               0.3478548451374538};
  // About 32K Gauss nodes in all, at least 4 per step.
  const int sub = std::max(1, 32768 / (n - 1));
  auto integrate = [&](double a, double b) {
    double s = 0.0;
    for (int k = 0; k < sub; ++k) {
      const double x0 = a + (b - a) * k / sub, x1 = a + (b - a) * (k + 1) / sub;
      const double c = 0.5 * (x0 + x1), h = 0.5 * (x1 - x0);
      for (int g = 0; g < 4; ++g) s += gw[g] * h * integrand(c + h * gx[g]);
    }
    return s;
  };
  // Points from the equator (t = pi) to the neck (t = 0); height accumulates inward (a
  // compensated sum: a million steps would otherwise lose 1e-8 of it).
  double h = 0.0, carry = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = M_PI * (1.0 - static_cast<double>(i) / (n - 1));
    if (i > 0) {
      const double y = integrate(t, M_PI * (1.0 - static_cast<double>(i - 1) / (n - 1))) - carry;
      const double sum = h + y;
      carry = (sum - h) - y;
      h = sum;
    }
    const double st = std::sin(0.5 * t);
    pts[i] = Vec2(r1 + (R - r1) * st * st, h);
  }
  pts.front().x() = R;
  pts.back().x() = r1;
  return pts;
}

namespace {

// The meridian edge of one dome in the XZ plane (x = r), from the equator vertex at z = z_eq to
// the opening vertex; `up` = +1 for the end dome (growing z), -1 for the start dome.
TopoDS_Edge dome_edge(const DomeParams& d, double R, double z_eq, double up, int samples,
                      const TopoDS_Vertex& v_eq, const TopoDS_Vertex& v_open) {
  const gp_Pnt c(0.0, 0.0, z_eq);
  if (d.type == DomeType::Isotensoid) {
    const std::vector<Vec2> m = dome_meridian(d, R, samples);
    Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, static_cast<int>(m.size()));
    for (std::size_t i = 0; i < m.size(); ++i) {
      pts->SetValue(static_cast<int>(i) + 1, gp_Pnt(m[i].x(), 0.0, z_eq + up * m[i].y()));
    }
    GeomAPI_Interpolate interp(pts, Standard_False, 1e-7);
    // Vertical tangents (along the axis) at the equator and at the neck.
    interp.Load(gp_Vec(0.0, 0.0, up), gp_Vec(0.0, 0.0, up), Standard_True);
    interp.Perform();
    if (!interp.IsDone()) throw InvariantError("isotensoid meridian interpolation failed");
    Handle(Geom_BSplineCurve) curve = interp.Curve();
    return BRepBuilderAPI_MakeEdge(curve, v_eq, v_open, curve->FirstParameter(),
                                   curve->LastParameter());
  }
  const double hgt = d.type == DomeType::Hemispherical ? R : d.aspect * R;
  if (hgt <= R) {
    // Major axis radial: P(u) = C + R cos u X + hgt sin u (up Z), equator at u = 0.
    const gp_Ax2 ax(c, gp_Dir(0.0, -up, 0.0), gp_Dir(1.0, 0.0, 0.0));
    const double u0 = std::acos(d.polar_opening / R);
    if (hgt == R) {
      Handle(Geom_Circle) circ = new Geom_Circle(ax, R);
      return BRepBuilderAPI_MakeEdge(circ, v_eq, v_open, 0.0, u0);
    }
    Handle(Geom_Ellipse) el = new Geom_Ellipse(ax, R, hgt);
    return BRepBuilderAPI_MakeEdge(el, v_eq, v_open, 0.0, u0);
  }
  // Major axis along the spindle: P(v) = C + hgt cos v (up Z) + R sin v X, equator at v = pi/2.
  const gp_Ax2 ax(c, gp_Dir(0.0, up, 0.0), gp_Dir(0.0, 0.0, up));
  Handle(Geom_Ellipse) el = new Geom_Ellipse(ax, hgt, R);
  const double v0 = std::asin(d.polar_opening / R);
  return BRepBuilderAPI_MakeEdge(el, v_open, v_eq, v0, M_PI / 2.0);
}

TopoDS_Shape solid_from_faces(const std::vector<TopoDS_Shape>& parts, const char* what) {
  BRepBuilderAPI_Sewing sew(1e-6);
  for (const TopoDS_Shape& s : parts) sew.Add(s);
  sew.Perform();
  const TopoDS_Shape sewn = sew.SewedShape();
  TopoDS_Shell shell;
  for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next()) {
    shell = TopoDS::Shell(ex.Current());
    break;
  }
  if (shell.IsNull()) throw InvariantError(std::string(what) + ": sewing gave no shell");
  BRepBuilderAPI_MakeSolid mk(shell);
  if (!mk.IsDone()) throw InvariantError(std::string(what) + ": could not make a solid");
  TopoDS_Solid solid = mk.Solid();
  BRepLib::OrientClosedSolid(solid);
  return solid;
}

}  // namespace

CadShape make_pipe(const PipeParams& p) {
  require_valid(p, "pipe");
  silence_occt_messages();
  return make_cad_shape(
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp::Origin(), gp::DZ()), p.radius, p.length).Shape());
}

CadShape make_sphere(double radius) {
  if (!positive(radius))
    throw ConfigError("sphere: radius must be > 0 mm (got " + num(radius) + ")");
  silence_occt_messages();
  return make_cad_shape(BRepPrimAPI_MakeSphere(gp::Origin(), radius).Shape());
}

CadShape make_cone(const ConeParams& p) {
  require_valid(p, "cone");
  silence_occt_messages();
  if (p.radius_start == p.radius_end) {
    return make_pipe(PipeParams{p.radius_start, p.length});
  }
  return make_cad_shape(
      BRepPrimAPI_MakeCone(gp_Ax2(gp::Origin(), gp::DZ()), p.radius_start, p.radius_end, p.length)
          .Shape());
}

CadShape make_vessel(const VesselParams& p) {
  require_valid(p, "vessel");
  silence_occt_messages();
  try {
    const double R = p.radius, L = p.length;
    const std::vector<Vec2> top = dome_meridian(p.dome_end, R, p.isotensoid_samples);
    const std::vector<Vec2> bot = dome_meridian(p.dome_start, R, p.isotensoid_samples);
    const TopoDS_Vertex v_top_eq = BRepBuilderAPI_MakeVertex(gp_Pnt(R, 0.0, L));
    const TopoDS_Vertex v_bot_eq =
        L > 0.0 ? BRepBuilderAPI_MakeVertex(gp_Pnt(R, 0.0, 0.0)).Vertex() : v_top_eq;
    const TopoDS_Vertex v_top_open =
        BRepBuilderAPI_MakeVertex(gp_Pnt(top.back().x(), 0.0, L + top.back().y()));
    const TopoDS_Vertex v_bot_open =
        BRepBuilderAPI_MakeVertex(gp_Pnt(bot.back().x(), 0.0, -bot.back().y()));

    BRepBuilderAPI_MakeWire wire;
    wire.Add(dome_edge(p.dome_end, R, L, +1.0, p.isotensoid_samples, v_top_eq, v_top_open));
    if (L > 0.0) wire.Add(BRepBuilderAPI_MakeEdge(v_top_eq, v_bot_eq).Edge());
    wire.Add(dome_edge(p.dome_start, R, 0.0, -1.0, p.isotensoid_samples, v_bot_eq, v_bot_open));
    if (!wire.IsDone()) throw InvariantError("vessel: the meridian wire is not connected");

    BRepPrimAPI_MakeRevol revol(wire.Wire(), gp_Ax1(gp::Origin(), gp::DZ()), 2.0 * M_PI);
    revol.Build();
    if (!revol.IsDone()) throw InvariantError("vessel: revolving the meridian failed");
    std::vector<TopoDS_Shape> parts{revol.Shape()};
    for (const TopoDS_Vertex& v : {v_top_open, v_bot_open}) {
      const TopTools_ListOfShape& gen = revol.Generated(v);
      if (gen.IsEmpty()) throw InvariantError("vessel: no circle at a polar opening");
      const TopoDS_Edge circle = TopoDS::Edge(gen.First());
      const gp_Pnt at = BRep_Tool::Pnt(v);
      BRepBuilderAPI_MakeFace cap(gp_Pln(gp_Pnt(0.0, 0.0, at.Z()), gp::DZ()),
                                  BRepBuilderAPI_MakeWire(circle).Wire());
      if (!cap.IsDone()) throw InvariantError("vessel: could not cap a polar opening");
      parts.push_back(cap.Face());
    }
    return make_cad_shape(solid_from_faces(parts, "vessel"));
  } catch (const Standard_Failure& e) {
    throw InvariantError(std::string("vessel: OpenCASCADE failed: ") + e.GetMessageString());
  }
}

namespace {

struct SpinePiece {
  bool bend = false;
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();           // line end points, or bend start/end
  Vec3 centre = Vec3::Zero(), axis = Vec3::UnitZ();  // bend only
  double radius = 0.0, angle = 0.0;
};

std::vector<SpinePiece> spine_pieces(const BentTubeParams& p, Vec3* start_dir) {
  Vec3 pos = Vec3::Zero(), d = Vec3::UnitZ(), u = Vec3::UnitX();
  *start_dir = d;
  std::vector<SpinePiece> out;
  for (std::size_t i = 0; i < p.segments.size(); ++i) {
    if (p.segments[i] > 0.0) {
      SpinePiece s;
      s.a = pos;
      s.b = pos + p.segments[i] * d;
      out.push_back(s);
      pos = s.b;
    }
    if (i >= p.bends.size()) break;
    const BendParams& bp = p.bends[i];
    const double phi = bp.plane_angle * M_PI / 180.0, th = bp.angle * M_PI / 180.0;
    const Vec3 toward = std::cos(phi) * u + std::sin(phi) * d.cross(u);  // unit, normal to d
    SpinePiece s;
    s.bend = true;
    s.centre = pos + bp.radius * toward;
    s.axis = d.cross(toward).normalized();
    s.radius = bp.radius;
    s.angle = th;
    const Eigen::AngleAxisd rot(th, s.axis);
    s.a = pos;
    s.b = s.centre + rot * (pos - s.centre);
    out.push_back(s);
    pos = s.b;
    d = (rot * d).normalized();
    u = (rot * u).normalized();  // parallel transport of the reference normal
  }
  return out;
}

}  // namespace

std::vector<Vec3> bent_tube_centreline(const BentTubeParams& p, int per_bend) {
  Vec3 d0;
  std::vector<Vec3> pts{Vec3::Zero()};
  for (const SpinePiece& s : spine_pieces(p, &d0)) {
    if (!s.bend) {
      pts.push_back(s.b);
      continue;
    }
    for (int k = 1; k <= per_bend; ++k) {
      const Eigen::AngleAxisd rot(s.angle * k / per_bend, s.axis);
      pts.push_back(s.centre + rot * (s.a - s.centre));
    }
  }
  return pts;
}

double bent_tube_length(const BentTubeParams& p) {
  double total = 0.0;
  for (double s : p.segments) total += s;
  for (const BendParams& b : p.bends) total += b.radius * b.angle * M_PI / 180.0;
  return total;
}

CadShape make_bent_tube(const BentTubeParams& p) {
  require_valid(p, "bent_tube");
  silence_occt_messages();
  try {
    Vec3 d0;
    const std::vector<SpinePiece> pieces = spine_pieces(p, &d0);
    BRepBuilderAPI_MakeWire spine;
    TopoDS_Vertex prev = BRepBuilderAPI_MakeVertex(pnt(pieces.front().a));
    for (const SpinePiece& s : pieces) {
      const TopoDS_Vertex next = BRepBuilderAPI_MakeVertex(pnt(s.b));
      if (!s.bend) {
        spine.Add(BRepBuilderAPI_MakeEdge(prev, next).Edge());
      } else {
        const gp_Ax2 ax(pnt(s.centre), dir(s.axis), dir((s.a - s.centre).normalized()));
        Handle(Geom_Circle) circ = new Geom_Circle(ax, s.radius);
        spine.Add(BRepBuilderAPI_MakeEdge(circ, prev, next, 0.0, s.angle).Edge());
      }
      prev = next;
    }
    if (!spine.IsDone()) throw InvariantError("bent_tube: the centreline wire is not connected");
    const gp_Circ section(gp_Ax2(gp::Origin(), dir(d0)), p.radius);
    const TopoDS_Face profile =
        BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(section)).Wire());
    BRepOffsetAPI_MakePipe pipe(spine.Wire(), profile);
    pipe.Build();
    if (!pipe.IsDone()) throw InvariantError("bent_tube: sweeping the section failed");
    TopoDS_Shape shape = pipe.Shape();
    for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) {
      TopoDS_Solid solid = TopoDS::Solid(ex.Current());
      BRepLib::OrientClosedSolid(solid);
      return make_cad_shape(solid);
    }
    throw InvariantError("bent_tube: the sweep gave no solid");
  } catch (const Standard_Failure& e) {
    throw InvariantError(std::string("bent_tube: OpenCASCADE failed: ") + e.GetMessageString());
  }
}

}  // namespace windplan
