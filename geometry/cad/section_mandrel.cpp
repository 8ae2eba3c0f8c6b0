#include "geometry/cad/section_mandrel.h"

#include <algorithm>
#include <cmath>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepLib.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <Bnd_Box.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Elips.hxx>
#include <gp_Trsf.hxx>

#include "geometry/base/errors.h"
#include "geometry/base/param_check.h"
#include "geometry/cad/cad_shape_occt.h"

namespace windplan {

namespace {

using param_check::fail;
using param_check::num;
using param_check::positive;

bool end_valid(const SectionEndParams& e, double half_x, const std::string& key, std::string* why) {
  if (!e.dome) return true;
  if (!positive(e.height))
    return fail(why, key + ".height must be > 0 mm (got " + num(e.height) + ")");
  if (!(positive(e.opening) && e.opening < half_x)) {
    return fail(why, key + ".opening (" + num(e.opening) +
                         " mm) must be > 0 and smaller than the section's half-width along X (" +
                         num(half_x) + " mm)");
  }
  return true;
}

// The section's closed wire in the plane z = 0, scaled by s about the axis.
TopoDS_Wire section_wire(const SectionParams& p, double s) {
  if (p.shape == SectionShape::Ellipse) {
    const double a = s * p.semi_x, b = s * p.semi_y;
    // gp_Elips needs major >= minor: put the major axis along X or Y.
    const gp_Ax2 ax = a >= b ? gp_Ax2(gp::Origin(), gp::DZ(), gp::DX())
                             : gp_Ax2(gp::Origin(), gp::DZ(), gp::DY());
    const gp_Elips el(ax, std::max(a, b), std::min(a, b));
    return BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(el).Edge()).Wire();
  }
  const double hx = 0.5 * s * p.width, hy = 0.5 * s * p.height, r = s * p.corner_radius;
  BRepBuilderAPI_MakeWire w;
  // Counter-clockwise seen from +Z: right side, top-right corner, top, ...
  const double cx[4] = {hx - r, -(hx - r), -(hx - r), hx - r};
  const double cy[4] = {hy - r, hy - r, -(hy - r), -(hy - r)};
  for (int k = 0; k < 4; ++k) {
    const double a0 = k * M_PI / 2.0, a1 = a0 + M_PI / 2.0;
    const gp_Pnt c(cx[k], cy[k], 0.0);
    const gp_Pnt p0(cx[k] + r * std::cos(a0), cy[k] + r * std::sin(a0), 0.0);
    const gp_Pnt p1(cx[k] + r * std::cos(a1), cy[k] + r * std::sin(a1), 0.0);
    // The straight side before this corner (from the previous corner's end), when not empty.
    const int j = (k + 3) % 4;
    const double b1 = (j + 1) * M_PI / 2.0;
    const gp_Pnt q(cx[j] + r * std::cos(b1), cy[j] + r * std::sin(b1), 0.0);
    if (q.Distance(p0) > 1e-9) w.Add(BRepBuilderAPI_MakeEdge(q, p0).Edge());
    const gp_Circ circ(gp_Ax2(c, gp::DZ(), gp::DX()), r);
    w.Add(BRepBuilderAPI_MakeEdge(circ, a0, a1).Edge());
  }
  if (!w.IsDone()) throw InvariantError("section: the rounded-rectangle wire is not connected");
  return w.Wire();
}

// A dome lofted from the section at z = z0 towards +Z (up = +1) or -Z (up = -1).
TopoDS_Shape dome(const SectionParams& p, const SectionEndParams& e, double z0, double up) {
  const int n = 9;
  const double u1 = std::acos(e.opening / p.half_x());
  BRepOffsetAPI_ThruSections loft(Standard_True, Standard_False, 1e-6);
  for (int k = 0; k < n; ++k) {
    const double u = u1 * k / (n - 1);
    const double z = z0 + up * e.height * std::sin(u) / std::sin(u1);
    gp_Trsf t;
    t.SetTranslation(gp_Vec(0.0, 0.0, z));
    loft.AddWire(TopoDS::Wire(
        BRepBuilderAPI_Transform(section_wire(p, std::cos(u)), t, Standard_True).Shape()));
  }
  loft.CheckCompatibility(Standard_False);
  loft.Build();
  if (!loft.IsDone()) throw InvariantError("section: lofting a dome failed");
  return loft.Shape();
}

TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b, const char* what) {
  BRepAlgoAPI_Fuse op(a, b);
  if (!op.IsDone())
    throw InvariantError(std::string("mandrel features: fusing the ") + what + " failed");
  return op.Shape();
}

TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b, const char* what) {
  BRepAlgoAPI_Cut op(a, b);
  if (!op.IsDone())
    throw InvariantError(std::string("mandrel features: cutting the ") + what + " failed");
  return op.Shape();
}

// The single solid of a boolean result, with coplanar and co-cylindrical faces merged.
TopoDS_Shape one_solid(const TopoDS_Shape& s, const char* what) {
  ShapeUpgrade_UnifySameDomain unify(s, Standard_True, Standard_True, Standard_False);
  unify.Build();
  const TopoDS_Shape u = unify.Shape();
  int count = 0;
  TopoDS_Solid solid;
  for (TopExp_Explorer ex(u, TopAbs_SOLID); ex.More(); ex.Next()) {
    if (count++ == 0) solid = TopoDS::Solid(ex.Current());
  }
  if (count != 1) {
    throw InvariantError(std::string(what) + ": expected one solid, got " + std::to_string(count));
  }
  BRepLib::OrientClosedSolid(solid);
  return solid;
}

TopoDS_Shape cylinder(double r, double z0, double z1, const gp_Pnt& at = gp::Origin()) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(at.X(), at.Y(), z0), gp::DZ()), r, z1 - z0).Shape();
}

}  // namespace

const char* to_string(SectionShape s) {
  return s == SectionShape::Ellipse ? "ellipse" : "rounded_rectangle";
}

SectionParams SectionParams::ellipse(double a, double b, double length) {
  SectionParams p;
  p.shape = SectionShape::Ellipse;
  p.semi_x = a;
  p.semi_y = b;
  p.length = length;
  return p;
}

SectionParams SectionParams::rounded_rectangle(double width, double height, double corner_radius,
                                               double length) {
  SectionParams p;
  p.shape = SectionShape::RoundedRectangle;
  p.width = width;
  p.height = height;
  p.corner_radius = corner_radius;
  p.length = length;
  return p;
}

bool SectionParams::is_valid(std::string* why) const {
  if (shape == SectionShape::Ellipse) {
    if (!positive(semi_x)) return fail(why, "semi_x must be > 0 mm (got " + num(semi_x) + ")");
    if (!positive(semi_y)) return fail(why, "semi_y must be > 0 mm (got " + num(semi_y) + ")");
  } else {
    if (!positive(width)) return fail(why, "width must be > 0 mm (got " + num(width) + ")");
    if (!positive(height)) return fail(why, "height must be > 0 mm (got " + num(height) + ")");
    if (!positive(corner_radius)) {
      return fail(why, "corner_radius must be > 0 mm (got " + num(corner_radius) + ")");
    }
    if (corner_radius > 0.5 * std::min(width, height) * (1.0 + 1e-12)) {
      return fail(why, "corner_radius (" + num(corner_radius) +
                           " mm) must be at most half the smaller of width and height (" +
                           num(0.5 * std::min(width, height)) + " mm)");
    }
  }
  if (!positive(length)) return fail(why, "length must be > 0 mm (got " + num(length) + ")");
  return end_valid(end_start, half_x(), "end_start", why) &&
         end_valid(end_end, half_x(), "end_end", why);
}

double section_perimeter(const SectionParams& p) {
  if (p.shape == SectionShape::Ellipse) {
    const double a = p.semi_x, b = p.semi_y, h = std::pow((a - b) / (a + b), 2);
    return M_PI * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
  }
  return 2.0 * (p.width + p.height) - (8.0 - 2.0 * M_PI) * p.corner_radius;
}

double section_radius(const SectionParams& p, double th) {
  const double c = std::cos(th), s = std::sin(th);
  if (p.shape == SectionShape::Ellipse) {
    const double a = p.semi_x, b = p.semi_y;
    return a * b / std::sqrt(b * b * c * c + a * a * s * s);
  }
  // Ray from the origin against the rounded rectangle (symmetric: work in the first quadrant).
  const double hx = 0.5 * p.width, hy = 0.5 * p.height, r = p.corner_radius;
  const double ac = std::abs(c), as = std::abs(s);
  const double t_side = std::min(ac > 1e-15 ? hx / ac : 1e300, as > 1e-15 ? hy / as : 1e300);
  const double x = t_side * ac, y = t_side * as;
  if (x <= hx - r || y <= hy - r) return t_side;
  // The corner circle centred (hx - r, hy - r): |t d - C| = r, the far root.
  const double cx = hx - r, cy = hy - r;
  const double bq = ac * cx + as * cy, cq = cx * cx + cy * cy - r * r;
  return bq + std::sqrt(std::max(0.0, bq * bq - cq));
}

CadShape make_section_mandrel(const SectionParams& p) {
  std::string why;
  if (!p.is_valid(&why)) throw ConfigError("section: " + why);
  silence_occt_messages();
  try {
    const TopoDS_Face base = BRepBuilderAPI_MakeFace(section_wire(p, 1.0)).Face();
    TopoDS_Shape body = BRepPrimAPI_MakePrism(base, gp_Vec(0.0, 0.0, p.length)).Shape();
    if (p.end_end.dome) body = fuse(body, dome(p, p.end_end, p.length, +1.0), "end dome");
    if (p.end_start.dome) body = fuse(body, dome(p, p.end_start, 0.0, -1.0), "start dome");
    if (p.end_end.dome || p.end_start.dome) body = one_solid(body, "section");
    return make_cad_shape(body);
  } catch (const Standard_Failure& e) {
    throw InvariantError(std::string("section: OpenCASCADE failed: ") + e.GetMessageString());
  }
}

bool MandrelFeatures::empty() const {
  return bore == 0.0 && shaft_start.radius == 0.0 && shaft_end.radius == 0.0 && flanges.empty() &&
         tabs.empty();
}

bool MandrelFeatures::is_valid(std::string* why, const std::string& key) const {
  if (!(std::isfinite(bore) && bore >= 0.0)) {
    return fail(why, key + ".bore must be >= 0 mm (got " + num(bore) + ")");
  }
  for (const auto& [name, s] :
       {std::pair{"shaft_start", shaft_start}, std::pair{"shaft_end", shaft_end}}) {
    if (!(std::isfinite(s.radius) && s.radius >= 0.0)) {
      return fail(why, key + "." + name + ".radius must be >= 0 mm");
    }
    if (s.radius > 0.0 && !positive(s.length)) {
      return fail(why, key + "." + name + ".length must be > 0 mm (got " + num(s.length) + ")");
    }
    if (s.radius > 0.0 && bore >= s.radius) {
      return fail(why, key + ".bore (" + num(bore) + " mm) must be smaller than " + name +
                           ".radius (" + num(s.radius) + " mm)");
    }
  }
  for (std::size_t i = 0; i < flanges.size(); ++i) {
    const FlangeParams& f = flanges[i];
    const std::string k = key + ".flanges[" + std::to_string(i) + "]";
    if (!std::isfinite(f.at)) return fail(why, k + ".at must be finite");
    if (!positive(f.radius)) return fail(why, k + ".radius must be > 0 mm");
    if (!positive(f.thickness)) return fail(why, k + ".thickness must be > 0 mm");
    if (f.bolts < 0) return fail(why, k + ".bolts must be >= 0");
    if (f.bolts > 0) {
      if (!positive(f.bolt_radius)) return fail(why, k + ".bolt_radius must be > 0 mm");
      if (!(f.pitch_radius + f.bolt_radius < f.radius)) {
        return fail(why, k + ": the bolt holes (pitch_radius " + num(f.pitch_radius) +
                             " + bolt_radius " + num(f.bolt_radius) +
                             " mm) must lie inside the flange radius (" + num(f.radius) + " mm)");
      }
    }
  }
  for (std::size_t i = 0; i < tabs.size(); ++i) {
    const TabParams& t = tabs[i];
    const std::string k = key + ".tabs[" + std::to_string(i) + "]";
    if (!std::isfinite(t.at) || !std::isfinite(t.angle))
      return fail(why, k + ".at and .angle must be finite");
    if (t.count < 1) return fail(why, k + ".count must be >= 1");
    if (t.count > 360) {
      // (count: 1e9 ran into OpenCASCADE's fuse and exit 3.)
      return fail(
          why, k + ".count must be <= 360 (one tab a degree; got " + std::to_string(t.count) + ")");
    }
    if (!positive(t.reach) || !positive(t.width) || !positive(t.thickness)) {
      return fail(why, k + ": reach, width and thickness must be > 0 mm");
    }
    if (!(std::isfinite(t.hole_radius) && t.hole_radius >= 0.0 &&
          2.0 * t.hole_radius < std::min(t.width, t.reach))) {
      return fail(why, k + ".hole_radius (" + num(t.hole_radius) +
                           " mm) must be >= 0 and below half the tab's width and reach");
    }
  }
  return true;
}

namespace {

// The angle (radians) half a tab spans about the axis where it leaves the wall.
double tab_half_angle(const TabParams& t, double r_wall) {
  return std::atan2(0.5 * t.width, r_wall);
}

// Tabs are separate blocks: neither the tabs of one ring (40 tabs 20 mm wide on a 50 mm wall
// fused into a collar, 29 s, exit 0) nor those of two rings at overlapping heights may overlap
// where they leave the wall.
void check_tabs_apart(const std::vector<TabParams>& tabs,
                      const std::function<double(double)>& outline) {
  auto angle_of = [](const TabParams& t, int k) {
    return t.angle * M_PI / 180.0 + 2.0 * M_PI * k / t.count;
  };
  auto apart = [](double a, double b) {
    const double d = std::fmod(std::fabs(a - b), 2.0 * M_PI);
    return std::min(d, 2.0 * M_PI - d);
  };
  for (std::size_t i = 0; i < tabs.size(); ++i) {
    for (std::size_t j = i; j < tabs.size(); ++j) {
      const TabParams &a = tabs[i], &b = tabs[j];
      if (j > i && !(a.at < b.at + b.thickness && b.at < a.at + a.thickness)) continue;
      for (int ka = 0; ka < a.count; ++ka) {
        for (int kb = (j == i ? ka + 1 : 0); kb < b.count; ++kb) {
          const double ta = angle_of(a, ka), tb = angle_of(b, kb);
          const double d = apart(ta, tb);
          const double need = tab_half_angle(a, outline(ta)) + tab_half_angle(b, outline(tb));
          if (d < need) {
            const std::string ki = "mandrel.features.tabs[" + std::to_string(i) + "]";
            const std::string kj = "mandrel.features.tabs[" + std::to_string(j) + "]";
            throw ConfigError(
                (j == i ? ki + ": its " + std::to_string(a.count) + " tabs overlap one another"
                        : ki + " and " + kj + " overlap") +
                " where they leave the wall (" + num(std::round(d * 1800.0 / M_PI) / 10.0) +
                " deg apart, " + num(std::round(need * 1800.0 / M_PI) / 10.0) + " deg needed for " +
                num(a.width) + " mm wide tabs there): " +
                (j == i ? "fewer or narrower tabs" : "move one ring's at or angle"));
          }
        }
      }
    }
  }
}

}  // namespace

CadShape add_mandrel_features(const CadShape& body_in, const MandrelFeatures& f,
                              const std::function<double(double)>& outline) {
  std::string why;
  if (!f.is_valid(&why)) throw ConfigError(why);
  if (f.empty()) return body_in;
  silence_occt_messages();
  try {
    if (body_in.empty()) throw InvariantError("mandrel features: empty body");
    TopoDS_Shape body = body_in.data()->shape;
    Bnd_Box box;
    BRepBndLib::AddOptimal(body, box, Standard_False, Standard_False);
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    const double span = z1 - z0;
    // Each flange and tab touches the body (a tab at 1000 mm on a 300 mm body, or a flange off
    // its shafts, left three solids: exit 3, "expected one solid").
    const double lo = z0 - f.shaft_start.length, hi = z1 + f.shaft_end.length;
    for (std::size_t i = 0; i < f.flanges.size(); ++i) {
      const FlangeParams& fl = f.flanges[i];
      if (!(fl.at < hi && fl.at + fl.thickness > lo)) {
        throw ConfigError("mandrel.features.flanges[" + std::to_string(i) + "].at = " + num(fl.at) +
                          " mm puts the flange (" + num(fl.at) + " to " +
                          num(fl.at + fl.thickness) +
                          " mm along the axis) off the mandrel, which " + "spans " + num(lo) +
                          " to " + num(hi) + " mm");
      }
    }
    for (std::size_t i = 0; i < f.tabs.size(); ++i) {
      const TabParams& t = f.tabs[i];
      if (!(t.at < z1 && t.at + t.thickness > z0)) {
        throw ConfigError("mandrel.features.tabs[" + std::to_string(i) + "].at = " + num(t.at) +
                          " mm puts the tabs (" + num(t.at) + " to " + num(t.at + t.thickness) +
                          " mm along the axis) off the body's wall, which spans " + num(z0) +
                          " to " + num(z1) + " mm");
      }
    }
    check_tabs_apart(f.tabs, outline);
    if (f.shaft_start.radius > 0.0) {
      body = fuse(body, cylinder(f.shaft_start.radius, z0 - f.shaft_start.length, z0 + 1e-3 * span),
                  "start shaft");
    }
    if (f.shaft_end.radius > 0.0) {
      body = fuse(body, cylinder(f.shaft_end.radius, z1 - 1e-3 * span, z1 + f.shaft_end.length),
                  "end shaft");
    }
    for (const FlangeParams& fl : f.flanges) {
      body = fuse(body, cylinder(fl.radius, fl.at, fl.at + fl.thickness), "flange");
    }
    for (const TabParams& t : f.tabs) {
      for (int k = 0; k < t.count; ++k) {
        const double th = t.angle * M_PI / 180.0 + 2.0 * M_PI * k / t.count;
        const double r_wall = outline(th);
        // A block from inside the wall (so that it fuses) to reach beyond it, in a frame turned
        // by th about the axis.
        const double r0 = 0.8 * r_wall, r1 = r_wall + t.reach;
        TopoDS_Shape block =
            BRepPrimAPI_MakeBox(gp_Pnt(r0, -0.5 * t.width, t.at), r1 - r0, t.width, t.thickness)
                .Shape();
        if (t.hole_radius > 0.0) {
          const double rc = r_wall + 0.5 * t.reach;
          block = cut(
              block,
              cylinder(t.hole_radius, t.at - 1.0, t.at + t.thickness + 1.0, gp_Pnt(rc, 0.0, 0.0)),
              "tab hole");
        }
        gp_Trsf rot;
        rot.SetRotation(gp_Ax1(gp::Origin(), gp::DZ()), th);
        body = fuse(body, BRepBuilderAPI_Transform(block, rot, Standard_True).Shape(), "tab");
      }
    }
    for (const FlangeParams& fl : f.flanges) {
      for (int k = 0; k < fl.bolts; ++k) {
        const double th = 2.0 * M_PI * (k + 0.5) / fl.bolts;
        const gp_Pnt c(fl.pitch_radius * std::cos(th), fl.pitch_radius * std::sin(th), 0.0);
        body = cut(body, cylinder(fl.bolt_radius, fl.at - 1.0, fl.at + fl.thickness + 1.0, c),
                   "bolt hole");
      }
    }
    if (f.bore > 0.0) {
      body = cut(body,
                 cylinder(f.bore, z0 - f.shaft_start.length - 1.0, z1 + f.shaft_end.length + 1.0),
                 "bore");
    }
    return make_cad_shape(one_solid(body, "mandrel features"));
  } catch (const Standard_Failure& e) {
    throw InvariantError(std::string("mandrel features: OpenCASCADE failed: ") +
                         e.GetMessageString());
  }
}

}  // namespace windplan
