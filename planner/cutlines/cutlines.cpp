#include "planner/cutlines/cutlines.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <tuple>

#include <Eigen/Eigenvalues>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/path_constraint.h"
#include "geometry/mesh/closest_point.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

namespace {

bool finite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

std::string label(const CutLineOptions& cut) {
  return "cut-line '" + (cut.name.empty() ? std::string("(unnamed)") : cut.name) + "'";
}

std::string vec_str(const Vec3& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

// The least-squares plane normal of points, perpendicular to `u` when u is non-zero.
Vec3 fit_normal(const std::vector<Vec3>& pts, const Vec3& u, const Vec3& fallback) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const Vec3& p : pts) C += (p - c) * (p - c).transpose();
  if (u.norm() == 0.0) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
    return es.eigenvectors().col(0).normalized();
  }
  // Restrict to the plane normal to u: a 2x2 problem in the basis (e1, e2).
  const Vec3 e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  Eigen::Matrix2d M;
  M << e1.dot(C * e1), e1.dot(C * e2), e2.dot(C * e1), e2.dot(C * e2);
  if (M.trace() <= 1e-24) return fallback;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(M);
  // A nearly straight curve (both eigenvalues ~0 relative to its extent) fits any plane.
  const Eigen::Vector2d w = es.eigenvectors().col(0);
  return (w.x() * e1 + w.y() * e2).normalized();
}

// A face point that sits on a corner is given as that vertex (geodesic_between rejects some
// corner face points: "initial path: the end point is not in the last strip face").
SurfacePoint clean_point(const Mesh& mesh, const SurfacePoint& p) {
  if (p.kind != SurfacePoint::Kind::Face) return p;
  for (int k = 0; k < 3; ++k) {
    if (p.bary[k] >= 1.0 - 1e-12) return SurfacePoint::at_vertex(mesh.triangle(p.element)[k]);
  }
  return p;
}

PlaneConstraint::Mode constraint_mode(const std::string& m) {
  return m == "fixed" ? PlaneConstraint::Mode::FixedNormal : PlaneConstraint::Mode::Free;
}

}  // namespace

bool CutLineOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (has_plane) {
    if (!finite(normal) || !(normal.norm() > 1e-12))
      return fail("plane.normal must be a non-zero vector");
    if (!std::isfinite(offset)) return fail("plane.offset must be a finite number (mm)");
  }
  if (has_station && !std::isfinite(station)) return fail("station must be a finite number (mm)");
  if (!normal_mode.empty() && normal_mode != "free" && normal_mode != "fixed" &&
      normal_mode != "cone") {
    return fail("normal_mode '" + normal_mode + "' is not one of: free, fixed, cone");
  }
  if (!(max_tilt_deg > 0.0 && max_tilt_deg <= 90.0)) {
    return fail("max_tilt_deg must be in (0, 90] degrees");
  }
  const int starts = int(has_plane) + int(has_station) + int(!init.empty());
  if (closed) {
    if (starts != 1) {
      return fail("a closed cut-line needs exactly one of plane, station, init (got " +
                  std::to_string(starts) + ")");
    }
  } else {
    if (has_station || !init.empty()) {
      return fail(
          "an open cut-line (closed: false) starts from its from/to points; station and "
          "init are for closed ones (plane may give the initial plane)");
    }
    if (!finite(from) || !finite(to)) return fail("from and to must be finite points (mm)");
    if (!((to - from).norm() > 1e-9)) return fail("an open cut-line needs from and to apart");
  }
  return true;
}

std::string CutLineSummary::brief_report() const {
  std::ostringstream s;
  s << "start " << start << " (length " << initial_length << " mm); result by " << method;
  if (polish_evaluations > 0) {
    s << " (" << polish_evaluations << " sections evaluated, " << polish_ms << " ms)";
  }
  s << ", tilt " << tilt_deg << " deg; refine_path: length " << refine_length << " mm, residual "
    << refine_residual << " mm, " << geodesic.brief_report() << "; total " << time_ms << " ms";
  return s.str();
}

namespace {

// Minimises the length of the section loop around the mandrel over the plane (Nelder-Mead with
// restarts on a local parametrisation n = normalise(n_c + a t1 + b t2), d = d_c + c * scale).
// The section of a plane is the only planar curve in that plane, so this is the coplanar
// geodesic problem reduced to the plane's three degrees of freedom; the length is piecewise
// smooth (it kinks where the plane passes a vertex), which a simplex method tolerates.
struct SectionFit {
  Vec3 n = Vec3::UnitZ();
  double d = 0.0;
  PlaneSection section;
  int evaluations = 0;
};

SectionFit minimise_section(const PlaneSectioner& S, const Vec3& n_start, double d_start,
                            const Vec3& near, const std::string& mode, const Vec3& n_initial,
                            double max_tilt, const Vec3* pivot = nullptr) {
  SectionFit best;
  best.n = n_start.normalized();
  best.d = pivot ? best.n.dot(*pivot) : d_start;
  if (!S.around_loop(best.n, best.d, &near, &best.section)) return best;
  const bool fixed = mode == "fixed";
  const bool cone = mode == "cone";
  // With a pivot the plane only turns about it (its offset follows the normal).
  const int dim = pivot ? (fixed ? 0 : 2) : (fixed ? 1 : 3);
  if (dim == 0) return best;
  double scale = std::max(best.section.length / (2.0 * M_PI), 1e-9);
  double step_angle = 0.02, step_offset = 0.02;
  for (int round = 0; round < 8; ++round) {
    const Vec3 nc = best.n, t1 = nc.unitOrthogonal(), t2 = nc.cross(t1);
    const double dc = best.d;
    const Vec3 ref = PlaneSectioner::centroid(best.section.points);
    auto plane_of = [&](const std::vector<double>& x, Vec3* n, double* d) {
      *n = fixed ? nc : Vec3((nc + x[0] * t1 + x[1] * t2).normalized());
      if (cone) {
        const double c = n->dot(n_initial);
        if (c < std::cos(max_tilt)) {
          Vec3 w = *n - c * n_initial;
          if (w.norm() < 1e-300) w = n_initial.unitOrthogonal();
          *n = std::cos(max_tilt) * n_initial + std::sin(max_tilt) * w.normalized();
        }
      }
      *d = pivot ? n->dot(*pivot) : dc + x[dim - 1] * scale;
    };
    PlaneSection sec;
    auto f = [&](const std::vector<double>& x) {
      Vec3 n;
      double d;
      plane_of(x, &n, &d);
      ++best.evaluations;
      if (!S.around_loop(n, d, &ref, &sec)) return std::numeric_limits<double>::infinity();
      return sec.length;
    };
    // Simplex.
    std::vector<std::vector<double>> X(dim + 1, std::vector<double>(dim, 0.0));
    for (int i = 0; i < dim; ++i) {
      X[i + 1][i] = !pivot && (fixed || i == dim - 1) ? step_offset : step_angle;
    }
    std::vector<double> F(dim + 1);
    for (int i = 0; i <= dim; ++i) F[i] = f(X[i]);
    const double start_value = F[0];
    for (int it = 0; it < 400 * dim; ++it) {
      std::vector<int> order(dim + 1);
      for (int i = 0; i <= dim; ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](int a, int b) { return F[a] < F[b]; });
      std::vector<std::vector<double>> X2;
      std::vector<double> F2;
      for (int i : order) X2.push_back(X[i]), F2.push_back(F[i]);
      X.swap(X2);
      F.swap(F2);
      double size = 0.0;
      for (int i = 1; i <= dim; ++i)
        for (int k = 0; k < dim; ++k) size = std::max(size, std::fabs(X[i][k] - X[0][k]));
      if (size < 1e-11 || (F[dim] - F[0]) <= 1e-15 * std::fabs(F[0])) break;
      std::vector<double> c(dim, 0.0);
      for (int i = 0; i < dim; ++i)
        for (int k = 0; k < dim; ++k) c[k] += X[i][k] / dim;
      auto along = [&](double t) {
        std::vector<double> y(dim);
        for (int k = 0; k < dim; ++k) y[k] = c[k] + t * (X[dim][k] - c[k]);
        return y;
      };
      const std::vector<double> xr = along(-1.0);
      const double fr = f(xr);
      if (fr < F[0]) {
        const std::vector<double> xe = along(-2.0);
        const double fe = f(xe);
        if (fe < fr)
          X[dim] = xe, F[dim] = fe;
        else
          X[dim] = xr, F[dim] = fr;
      } else if (fr < F[dim - 1]) {
        X[dim] = xr, F[dim] = fr;
      } else {
        const std::vector<double> xc = fr < F[dim] ? along(-0.5) : along(0.5);
        const double fc = f(xc);
        if (fc < std::min(fr, F[dim])) {
          X[dim] = xc, F[dim] = fc;
        } else {
          for (int i = 1; i <= dim; ++i) {
            for (int k = 0; k < dim; ++k) X[i][k] = X[0][k] + 0.5 * (X[i][k] - X[0][k]);
            F[i] = f(X[i]);
          }
        }
      }
    }
    int b = 0;
    for (int i = 1; i <= dim; ++i)
      if (F[i] < F[b]) b = i;
    if (!(F[b] < best.section.length * (1.0 - 1e-13))) {
      // No progress from this centre: restart once with smaller steps, then stop.
      if (step_angle < 1e-3) break;
      step_angle *= 0.1;
      step_offset *= 0.1;
      continue;
    }
    Vec3 n;
    double d;
    plane_of(X[b], &n, &d);
    PlaneSection s2;
    if (!S.around_loop(n, d, &ref, &s2)) break;
    const double gain = best.section.length - s2.length;
    best.n = n;
    best.d = d;
    best.section = std::move(s2);
    scale = std::max(best.section.length / (2.0 * M_PI), 1e-9);
    (void)start_value;
    if (gain <= 1e-14 * best.section.length) break;
  }
  return best;
}

// Open cut-lines: the plane contains a and b, so only its rotation phi about the line a-b is
// free; minimise the length of the section arc between them over phi (bracketing, then golden
// section), starting at phi_start. phi is measured from e1 (the initial normal) towards e2.
struct ArcFit {
  Vec3 n = Vec3::UnitZ();
  double d = 0.0;
  std::vector<Vec3> points;
  double length = std::numeric_limits<double>::infinity();
  int evaluations = 0;
};

ArcFit minimise_arc(const PlaneSectioner& S, const Vec3& a, const Vec3& b, const Vec3& e1,
                    double phi_start, double max_phi, double tol) {
  const Vec3 u = (b - a).normalized();
  const Vec3 e2 = u.cross(e1).normalized();
  ArcFit best;
  auto eval = [&](double phi) {
    const Vec3 n = std::cos(phi) * e1 + std::sin(phi) * e2;
    const double d = n.dot(a);
    ++best.evaluations;
    std::vector<Vec3> pts = arc_between(S.sections(n, d), a, b, tol);
    const double len =
        pts.empty() ? std::numeric_limits<double>::infinity() : polyline_length(pts, false);
    if (len < best.length) best.n = n, best.d = d, best.points = std::move(pts), best.length = len;
    return len;
  };
  auto clampphi = [&](double p) { return std::clamp(p, -max_phi, max_phi); };
  double x0 = clampphi(phi_start);
  double f0 = eval(x0);
  if (max_phi <= 0.0) return best;
  // Bracket a minimum: walk downhill with growing steps.
  double h = 0.01;
  double xl = clampphi(x0 - h), xr = clampphi(x0 + h);
  double fl = eval(xl), fr = eval(xr);
  if (fl < f0 || fr < f0) {
    const double dir = fl < fr ? -1.0 : 1.0;
    double xa = x0, xb = dir < 0 ? xl : xr, fb = std::min(fl, fr);
    for (int k = 0; k < 40; ++k) {
      h *= 1.6;
      const double xc = clampphi(xb + dir * h);
      const double fc = eval(xc);
      if (!(fc < fb) || xc == xb) {
        xl = std::min(xa, xc), xr = std::max(xa, xc);
        break;
      }
      xa = xb, xb = xc, fb = fc;
      xl = std::min(xa, xb), xr = std::max(xa, xb);
    }
  }
  // Golden section on [xl, xr].
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = xr - g * (xr - xl), dd = xl + g * (xr - xl);
  double fc = eval(c), fd = eval(dd);
  for (int k = 0; k < 80 && xr - xl > 1e-11; ++k) {
    if (fc < fd) {
      xr = dd, dd = c, fd = fc, c = xr - g * (xr - xl), fc = eval(c);
    } else {
      xl = c, c = dd, fc = fd, dd = xl + g * (xr - xl), fd = eval(dd);
    }
  }
  return best;
}

}  // namespace

std::vector<Vec3> read_curve_csv(const std::filesystem::path& file) {
  const std::string text = read_text_file(file);
  std::vector<Vec3> pts;
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  bool header_allowed = true;  // the first non-comment line may be a header
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto b = line.find_first_not_of(" \t");
    if (b == std::string::npos || line[b] == '#') continue;
    std::string cell;
    std::vector<std::string> cells;
    std::istringstream ls(line);
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    double v[3];
    bool ok = cells.size() == 3;
    for (int k = 0; ok && k < 3; ++k) {
      const char* c = cells[k].c_str();
      char* end = nullptr;
      v[k] = std::strtod(c, &end);
      while (end && (*end == ' ' || *end == '\t')) ++end;
      ok = end != c && end && *end == '\0' && std::isfinite(v[k]);
    }
    if (!ok) {
      const char c0 = line[b];
      if (header_allowed && (std::isalpha(static_cast<unsigned char>(c0)) || c0 == '"')) {
        header_allowed = false;
        continue;
      }
      throw IoError(file.string() + ":" + std::to_string(lineno) +
                    ": expected three numbers x,y,z (mm), got '" + line + "'");
    }
    header_allowed = false;
    pts.emplace_back(v[0], v[1], v[2]);
  }
  return pts;
}

CutLine compute_cutline(const Mesh& mesh, const CutLineOptions& cut, const SpindleAxis& axis,
                        const GeodesicOptions& geodesic, CutLineSummary* summary) {
  using Clock = std::chrono::steady_clock;
  auto ms_since = [](Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
  };
  const Clock::time_point t_start = Clock::now();
  const std::string what = label(cut);
  if (std::string why; !cut.is_valid(&why)) throw ConfigError(what + ": " + why);
  if (mesh.num_faces() == 0) throw InputError(what + ": the mesh has no faces");
  CutLineSummary sum;
  const double diag = mesh.bounding_box().diagonal_length();
  const double snap_distance = 0.05 * diag;  // curve points farther from the surface are errors
  GeodesicOptions opts = geodesic;
  opts.constraint_tolerance = std::min(opts.constraint_tolerance, 1e-9);
  if (std::string why; !opts.is_valid(&why)) throw ConfigError(what + ": geodesic options: " + why);

  SurfacePath initial;
  Vec3 n0;
  double d0 = 0.0;
  try {
    if (cut.closed) {
      if (cut.has_plane || cut.has_station) {
        n0 = cut.has_plane ? cut.normal.normalized() : axis.direction.normalized();
        d0 = cut.has_plane ? cut.offset : n0.dot(axis.origin) + cut.station;
        sum.start = cut.has_plane ? "plane" : "station";
        PlaneSection sec = axial_plane_section(mesh, n0, d0, axis, what);
        initial = std::move(sec.path);
        sum.initial_length = sec.length;
      } else {
        sum.start = "init";
        std::vector<Vec3> pts = read_curve_csv(cut.init);
        if (pts.size() >= 2 && (pts.front() - pts.back()).norm() <= 1e-9 * (1.0 + diag)) {
          pts.pop_back();  // the closing point repeated
        }
        if (pts.size() < 3) {
          throw InputError(what + ": " + cut.init.string() + " has " + std::to_string(pts.size()) +
                           " point(s); a closed curve needs at least 3");
        }
        double longest = 0.0;
        for (std::size_t i = 1; i < pts.size(); ++i)
          longest = std::max(longest, (pts[i] - pts[i - 1]).norm());
        const double gap = (pts.front() - pts.back()).norm();
        if (gap > 2.0 * longest) {
          std::ostringstream s;
          s << what << ": the curve in " << cut.init.string() << " is not closed: its first and "
            << "last points are " << gap << " mm apart (the longest step between points is "
            << longest << " mm); give a loop or set closed: false";
          throw InputError(s.str());
        }
        n0 = fit_normal(pts, Vec3::Zero(), axis.direction);
        if (n0.dot(axis.direction) < 0.0) n0 = -n0;
        Vec3 c = Vec3::Zero();
        for (const Vec3& p : pts) c += p;
        d0 = n0.dot(c / static_cast<double>(pts.size()));
        const EdgeGraph graph = build_edge_graph(mesh);
        initial = path_from_curve(mesh, graph, pts, true, snap_distance);
        sum.initial_length = euclidean_length(mesh, initial);
        // The start's planar section (the fitted plane's loop), when there is one: the result is
        // never longer than it.
        PlaneSection fitted;
        const Vec3 mid = PlaneSectioner::centroid(pts);
        if (PlaneSectioner(mesh, axis).around_loop(n0, d0, &mid, &fitted)) {
          sum.initial_length = std::min(sum.initial_length, fitted.length);
        }
      }
    } else {
      sum.start = "geodesic";
      const ClosestPointQuery cpq(mesh);
      const ClosestPointQuery::Hit ha = cpq.closest(cut.from), hb = cpq.closest(cut.to);
      for (const auto& [hit, key, p] :
           {std::tuple{ha, "from", cut.from}, std::tuple{hb, "to", cut.to}}) {
        if (!(hit.distance <= snap_distance)) {
          std::ostringstream s;
          s << what << ": " << key << " " << vec_str(p) << " is " << hit.distance
            << " mm from the surface (at most " << snap_distance << " mm)";
          throw InputError(s.str());
        }
      }
      const Vec3 u = (hb.position - ha.position).normalized();
      const GeodesicContext ctx(mesh);
      const OpenGeodesicResult g =
          geodesic_between(ctx, clean_point(mesh, ha.point), clean_point(mesh, hb.point), geodesic);
      initial = g.path;
      sum.initial_length = euclidean_length(mesh, initial);
      const int fa = containing_face(mesh, ha.point);
      const Vec3 fallback = u.cross(mesh.face_normal(fa)).normalized();
      if (cut.has_plane) {
        n0 = cut.normal.normalized();
        n0 = n0 - n0.dot(u) * u;
        if (!(n0.norm() > 1e-6)) {
          throw InputError(what +
                           ": plane.normal is parallel to the line from -> to; no plane "
                           "with that normal contains both points");
        }
        n0.normalize();
      } else {
        n0 = fit_normal(polyline(mesh, initial), u, fallback);
      }
      d0 = n0.dot(ha.position);
    }
  } catch (const IoError&) {
    throw;
  } catch (const ConfigError&) {
    throw;
  } catch (const InputError& e) {
    const std::string m = e.what();
    throw InputError(m.rfind(what, 0) == 0 ? m : what + ": " + m);
  }
  sum.initial_normal = n0;
  sum.initial_offset = d0;

  // A station keeps its plane unless the job frees the normal; a plane or station start keeps
  // its offset (the plane turns about the start loop's centre) unless keep_offset is false: on a
  // cylinder every perpendicular loop is equally short, so a free offset drifts.
  const std::string mode = !cut.normal_mode.empty() ? cut.normal_mode
                           : cut.has_station        ? "fixed"
                                                    : "free";
  const double tilt = mode == "cone" ? cut.max_tilt_deg * M_PI / 180.0 : M_PI;
  if (cut.closed && cut.keep_offset && (cut.has_plane || cut.has_station)) {
    const PlaneSectioner S(mesh, axis);
    // The pivot: the centre of the start loop (in the start plane, so the offset is kept; in a
    // bend it lies near the centreline, about which the cross-sections turn).
    const Vec3 pivot = PlaneSectioner::centroid(polyline(mesh, initial));
    const SectionFit fit = minimise_section(S, n0, d0, pivot, mode, n0, tilt, &pivot);
    if (!fit.section.around) {
      throw InputError(what +
                       ": the plane through the start has no section loop around the "
                       "mandrel");
    }
    CutLine out;
    out.name = cut.name;
    out.closed = true;
    Vec3 fn = fit.n;
    double fd = fit.d;
    if (fn.dot(n0) < 0.0) fn = -fn, fd = -fd;
    out.points = fit.section.points;
    out.plane_normal = fn;
    out.plane_offset = fd;
    out.length = fit.section.length;
    for (const Vec3& p : out.points)
      out.residual = std::max(out.residual, std::fabs(fn.dot(p) - fd));
    sum.method = "section polish";
    sum.polish_evaluations = fit.evaluations;
    sum.tilt_deg = std::acos(std::clamp(fn.dot(n0), -1.0, 1.0)) * 180.0 / M_PI;
    sum.time_ms = ms_since(t_start);
    if (summary) *summary = std::move(sum);
    return out;
  }
  PlaneConstraint plane(n0, d0, constraint_mode(mode), tilt);
  GeodesicResult r = refine_path(mesh, initial, {}, opts, &plane);
  Vec3 n = plane.normal(r.constraint_variables.data());
  double d = plane.offset(r.constraint_variables.data());
  if (n.dot(n0) < 0.0) {
    n = -n;
    d = -d;
  }

  CutLine out;
  out.name = cut.name;
  out.closed = cut.closed;
  out.points = polyline(mesh, r.path);
  out.plane_normal = n;
  out.plane_offset = d;
  out.length = euclidean_length(mesh, r.path);
  for (const Vec3& p : out.points) out.residual = std::max(out.residual, std::fabs(n.dot(p) - d));
  sum.method = "refine_path";
  sum.refine_length = out.length;
  sum.refine_residual = out.residual;
  sum.refine_normal = n;

  const Clock::time_point t_polish = Clock::now();
  if (!cut.closed) {
    // Polish the rotation of the plane about the line from -> to by minimising the exact section
    // arc between the two points (the refinement can stall; see CutLineSummary::method).
    const PlaneSectioner S(mesh, axis);
    const Vec3 a = out.points.front(), b = out.points.back();
    const Vec3 u = (b - a).normalized();
    const Vec3 e2 = u.cross(n0).normalized();
    double phi = std::atan2(n.dot(e2), n.dot(n0));
    if (phi > M_PI / 2) phi -= M_PI;
    if (phi < -M_PI / 2) phi += M_PI;
    const double max_phi = mode == "fixed" ? 0.0 : mode == "cone" ? tilt : M_PI / 2;
    const ArcFit fit = minimise_arc(S, a, b, n0, phi, max_phi, 1e-7 * (1.0 + diag));
    sum.polish_evaluations = fit.evaluations;
    const bool refine_ok = r.summary.converged() && out.residual <= 1e-6 * out.length;
    if (!fit.points.empty() && (!refine_ok || fit.length <= out.length * (1.0 + 1e-9))) {
      out.points = fit.points;
      out.plane_normal = n = fit.n;
      out.plane_offset = fit.d;
      out.length = fit.length;
      out.residual = 0.0;
      for (const Vec3& p : out.points) {
        out.residual = std::max(out.residual, std::fabs(fit.n.dot(p) - fit.d));
      }
      sum.method = "section polish";
    }
  }
  if (cut.closed) {
    // The refinement may stop early (it can get stuck on vertices while the plane turns): polish
    // the plane by minimising the length of its exact section loop, from the refined plane (or
    // the initial one), and keep the polished loop unless the refined one is clearly shorter.
    const PlaneSectioner S(mesh, axis);
    SectionFit fit =
        minimise_section(S, n, d, PlaneSectioner::centroid(out.points), mode, n0, tilt);
    if (!fit.section.around) {
      fit = minimise_section(S, n0, d0, PlaneSectioner::centroid(out.points), mode, n0, tilt);
    }
    sum.polish_evaluations = fit.evaluations;
    const bool refine_ok = r.summary.converged() && out.residual <= 1e-6 * out.length;
    if (fit.section.around && (!refine_ok || fit.section.length <= out.length * (1.0 + 1e-9))) {
      Vec3 fn = fit.n;
      double fd = fit.d;
      if (fn.dot(n0) < 0.0) fn = -fn, fd = -fd;
      out.points = std::move(fit.section.points);
      out.plane_normal = fn;
      out.plane_offset = fd;
      out.length = fit.section.length;
      out.residual = 0.0;
      for (const Vec3& p : out.points) {
        out.residual = std::max(out.residual, std::fabs(fn.dot(p) - fd));
      }
      n = fn;
      sum.method = "section polish";
    }
  }

  sum.polish_ms = ms_since(t_polish);
  sum.tilt_deg = std::acos(std::clamp(n.dot(n0), -1.0, 1.0)) * 180.0 / M_PI;
  sum.geodesic = r.summary;
  {
    const ClosestPointQuery cpq(mesh);
    for (const Vec3& p : out.points) {
      sum.max_surface_distance = std::max(sum.max_surface_distance, cpq.closest(p).distance);
    }
  }
  if (!r.summary.converged() && sum.method == "refine_path") {
    sum.warnings.push_back(what + ": the refinement stopped with " +
                           std::string(to_string(r.summary.termination)) + " (" +
                           r.summary.message + ")");
  }
  if (out.residual > 1e-6 * out.length) {
    std::ostringstream s;
    s << what << ": plane residual " << out.residual << " mm is above 1e-6 of the length "
      << out.length << " mm";
    sum.warnings.push_back(s.str());
  }
  sum.time_ms = ms_since(t_start);
  if (summary) *summary = std::move(sum);
  return out;
}

std::vector<CutLine> compute_cutlines(const Mesh& winding_surface, const SpindleAxis& axis,
                                      const std::vector<CutLineOptions>& cuts,
                                      const GeodesicOptions& geodesic,
                                      std::vector<CutLineSummary>* summaries) {
  std::vector<CutLine> out;
  if (summaries) summaries->clear();
  for (const CutLineOptions& c : cuts) {
    CutLineSummary s;
    out.push_back(compute_cutline(winding_surface, c, axis, geodesic, &s));
    if (summaries) summaries->push_back(std::move(s));
  }
  return out;
}

}  // namespace windplan
