#include "planner/winding/coverage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/mesh/closest_point.h"
#include "geometry/region/plane_section.h"

namespace windplan {

namespace {

struct Band {
  double u = 0.0;      // centre, mm along the loop
  double trace = 0.0;  // mm along the loop
  double sin = 1.0;    // sin of the angle between fibre and loop
};

struct Loop {
  std::vector<Vec3> pts;
  std::vector<double> cum;  // cum[i]: arc length at pts[i]; cum.back(): the loop length
  double length = 0.0;
};

Loop make_loop(const std::vector<Vec3>& pts) {
  Loop l;
  l.pts = pts;
  l.cum.push_back(0.0);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    l.cum.push_back(l.cum.back() + (pts[(i + 1) % pts.size()] - pts[i]).norm());
  }
  l.length = l.cum.back();
  return l;
}

// Arc length of the point of the loop nearest q, and the loop's unit tangent there.
double locate(const Loop& l, const Vec3& q, Vec3* tangent) {
  double best = std::numeric_limits<double>::infinity(), u = 0.0;
  const std::size_t n = l.pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = l.pts[i], b = l.pts[(i + 1) % n], ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - q).squaredNorm();
    if (d < best) {
      best = d;
      u = l.cum[i] + t * (l.cum[i + 1] - l.cum[i]);
      if (len2 > 0.0) *tangent = ab.normalized();
    }
  }
  return u;
}

// The longest closed contour {h = level} of a per-vertex field on a triangle mesh (empty when
// none closes): one segment per face the level crosses, chained through the crossed edges.
std::vector<Vec3> level_loop(const Mesh& m, const std::vector<double>& h, double level) {
  auto above = [&](int v) { return h[v] >= level; };
  auto key = [](int a, int b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); };
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;  // crossed edge -> faces
  std::map<int, std::array<std::pair<int, int>, 2>> face_edges;   // face -> its two crossed edges
  for (int f = 0; f < m.num_faces(); ++f) {
    const Tri& t = m.triangle(f);
    std::vector<std::pair<int, int>> crossed;
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (above(a) != above(b)) crossed.push_back(key(a, b));
    }
    if (crossed.size() != 2) continue;
    face_edges[f] = {crossed[0], crossed[1]};
    for (const auto& e : crossed) faces_of_edge[e].push_back(f);
  }
  auto point = [&](const std::pair<int, int>& e) {
    const double t = (level - h[e.first]) / (h[e.second] - h[e.first]);
    return Vec3(m.position(e.first) + t * (m.position(e.second) - m.position(e.first)));
  };
  std::vector<Vec3> best;
  double best_len = 0.0;
  std::map<int, bool> used;
  for (const auto& [f0, edges] : face_edges) {
    if (used[f0]) continue;
    std::vector<Vec3> loop;
    int f = f0;
    std::pair<int, int> e = edges[0];
    bool closed = false;
    while (true) {
      used[f] = true;
      const auto& fe = face_edges[f];
      const std::pair<int, int> next = fe[0] == e ? fe[1] : fe[0];
      loop.push_back(point(next));
      const std::vector<int>& nb = faces_of_edge[next];
      int g = -1;
      for (int x : nb) {
        if (x != f) g = x;
      }
      if (g < 0) break;  // the mesh boundary: an open contour
      if (g == f0) {
        closed = true;
        break;
      }
      if (used[g]) break;
      f = g;
      e = next;
    }
    if (!closed || loop.size() < 3) continue;
    double len = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i)
      len += (loop[(i + 1) % loop.size()] - loop[i]).norm();
    if (len > best_len) best_len = len, best = std::move(loop);
  }
  return best;
}

struct Sweep {
  double bare = 0.0, widest_gap = 0.0;
  int max_stack = 0;
};

// Sweeps the bands of one family round a loop of length L.
Sweep sweep(const std::vector<Band>& bands, double L) {
  Sweep s;
  if (bands.empty()) {
    s.bare = L;
    s.widest_gap = L;
    return s;
  }
  std::vector<std::pair<double, int>> ev;
  int count0 = 0;  // bands covering u = 0
  for (const Band& b : bands) {
    if (b.trace >= L) {
      ++count0;
      continue;
    }
    double a = std::fmod(b.u - 0.5 * b.trace, L);
    if (a < 0.0) a += L;
    double e = a + b.trace;
    if (e >= L) {
      ++count0;
      e -= L;
    }
    ev.emplace_back(a, +1);
    ev.emplace_back(e, -1);
  }
  std::sort(ev.begin(), ev.end());
  int count = count0;
  s.max_stack = count;
  // Uncovered runs; the one that starts at u = 0 joins the one that ends at L (a circle).
  const bool at_start = count == 0;
  bool in_run = at_start, first_closed = false;
  double prev = 0.0, run = 0.0, first = 0.0;
  for (const auto& [u, d] : ev) {
    if (in_run) run += u - prev;
    count += d;
    s.max_stack = std::max(s.max_stack, count);
    if (in_run && count > 0) {
      if (at_start && !first_closed) {
        first = run;
        first_closed = true;
      } else {
        s.widest_gap = std::max(s.widest_gap, run);
      }
      s.bare += run;
      in_run = false;
      run = 0.0;
    } else if (!in_run && count == 0) {
      in_run = true;
      run = 0.0;
    }
    prev = u;
  }
  if (in_run) {
    run += L - prev;
    s.bare += run;
    s.widest_gap = std::max(s.widest_gap, run + (at_start && first_closed ? first : 0.0));
  } else if (at_start && first_closed) {
    s.widest_gap = std::max(s.widest_gap, first);
  }
  return s;
}

double cv(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  double m = 0.0;
  for (double x : v) m += x;
  m /= v.size();
  double q = 0.0;
  for (double x : v) q += (x - m) * (x - m);
  return m > 0.0 ? std::sqrt(q / v.size()) / m : 0.0;
}

std::string fmt(const char* f, double v) { return format_number(f, v); }

}  // namespace

bool CoverageOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (!(band_width > 0.0) || !std::isfinite(band_width)) return fail("band_width must be > 0 mm");
  if (stations < 1) return fail("stations must be >= 1");
  if (!std::isnan(end_margin) && !(end_margin >= 0.0 && std::isfinite(end_margin))) {
    return fail("end_margin must be >= 0 mm");
  }
  return true;
}

std::string CoverageReport::brief_report() const {
  if (!measured()) {
    return centre_line
               ? "not measured (no section normal to the centre line goes around the tube)"
               : "not measured (no station plane cuts the mandrel in a loop around the axis)";
  }
  return "bare " + fmt("%.2f", 100.0 * bare_fraction) + "% (widest gap " + fmt("%.1f", widest_gap) +
         " mm), widest overlap " + fmt("%.2f", widest_overlap) + " mm (" +
         fmt("%.2f", widest_overlap_largest) + " on the largest sections), up to " +
         std::to_string(max_stack) + " bands stacked, cover factor " + fmt("%.3f", cover_factor) +
         ", " + fmt("%.2f", mean_plies) + " plies, at " + std::to_string(stations.size()) +
         (centre_line ? " sections normal to the centre line" : " stations");
}

CoverageReport measure_coverage(const Mesh& surface, const SpindleAxis& axis,
                                const std::vector<Circuit>& circuits,
                                const CoverageOptions& options) {
  if (std::string why; !options.is_valid(&why)) throw ConfigError("coverage: " + why);
  const Vec3 d = axis.direction.normalized();
  std::vector<std::vector<Vec3>> passes;
  double xa = std::numeric_limits<double>::infinity(), xb = -xa;
  for (const Circuit& c : circuits) {
    for (const CircuitSegment& seg : c.segments) {
      if (seg.kind != CircuitSegment::Kind::Pass) continue;
      std::vector<Vec3> p;
      for (int i = seg.first; i <= seg.last; ++i) {
        p.push_back(c.points[i].position);
        xa = std::min(xa, axis.axial(p.back()));
        xb = std::max(xb, axis.axial(p.back()));
      }
      passes.push_back(std::move(p));
    }
  }
  CoverageReport rep;
  if (passes.empty()) return rep;
  // The station coordinate of a point: its axial position, or the height field's value at its
  // closest point on the surface.
  const std::vector<double>* hf = options.height;
  if (hf && static_cast<int>(hf->size()) != surface.num_vertices()) {
    throw InputError("coverage: the height field has " + std::to_string(hf->size()) +
                     " values for " + std::to_string(surface.num_vertices()) + " vertices");
  }
  std::unique_ptr<ClosestPointQuery> cpq;
  std::vector<std::vector<double>> coord(passes.size());
  double lo = 0.0, hi = 0.0;
  const Spine* spine = options.spine && !options.spine->empty() ? options.spine : nullptr;
  std::unique_ptr<PlaneSectioner> sectioner;
  if (spine) {  // arc length along the centre line
    hf = nullptr;
    sectioner = std::make_unique<PlaneSectioner>(surface, axis);
    double sa = std::numeric_limits<double>::infinity(), sb = -sa;
    for (std::size_t k = 0; k < passes.size(); ++k) {
      for (const Vec3& p : passes[k]) {
        coord[k].push_back(spine->project(p));
        sa = std::min(sa, coord[k].back());
        sb = std::max(sb, coord[k].back());
      }
    }
    const double margin = std::isnan(options.end_margin) ? options.band_width : options.end_margin;
    lo = sa + margin;
    hi = sb - margin;
    rep.centre_line = true;
    rep.centre_line_length = spine->length();
  } else if (hf) {
    cpq = std::make_unique<ClosestPointQuery>(surface);
    double ha = std::numeric_limits<double>::infinity(), hb = -ha;
    for (std::size_t k = 0; k < passes.size(); ++k) {
      for (const Vec3& p : passes[k]) {
        const ClosestPointQuery::Hit hit = cpq->closest(p);
        const Tri& t = surface.triangle(hit.point.element);
        const Vec3& b = hit.point.bary;
        coord[k].push_back(b[0] * (*hf)[t[0]] + b[1] * (*hf)[t[1]] + b[2] * (*hf)[t[2]]);
        ha = std::min(ha, coord[k].back());
        hb = std::max(hb, coord[k].back());
      }
    }
    lo = ha + 0.05 * (hb - ha);
    hi = hb - 0.05 * (hb - ha);
  } else {
    for (std::size_t k = 0; k < passes.size(); ++k) {
      for (const Vec3& p : passes[k]) coord[k].push_back(axis.axial(p));
    }
    const double margin = std::isnan(options.end_margin) ? options.band_width : options.end_margin;
    lo = xa + margin;
    hi = xb - margin;
  }
  if (!(hi > lo)) return rep;
  const double B = options.band_width;
  double plies_sum = 0.0;
  rep.cover_factor = std::numeric_limits<double>::infinity();
  for (int k = 0; k < options.stations; ++k) {
    const double x = lo + (hi - lo) * (k + 0.5) / options.stations;
    Loop loop;
    Vec3 c0 = Vec3::Zero(), t0 = Vec3::UnitZ();  // the station's centre point and plane normal
    double reach = 0.0;  // crossings farther than this from c0 belong to another part of the tube
    if (spine) {
      c0 = spine->point(x);
      t0 = spine->tangent(x);
      PlaneSection sec;
      if (!sectioner->around_loop(t0, t0.dot(c0), &c0, &sec)) {
        ++rep.skipped;
        continue;
      }
      loop = make_loop(sec.points);
      for (const Vec3& p : sec.points) reach = std::max(reach, 1.5 * (p - c0).norm());
    } else if (hf) {
      const std::vector<Vec3> pts = level_loop(surface, *hf, x);
      if (pts.empty()) {
        ++rep.skipped;
        continue;
      }
      loop = make_loop(pts);
    } else {
      try {
        loop = make_loop(
            axial_plane_section(surface, d, d.dot(axis.origin) + x, axis, "coverage station")
                .points);
      } catch (const InputError&) {
        ++rep.skipped;
        continue;
      }
    }
    if (!(loop.length > 0.0)) {
      ++rep.skipped;
      continue;
    }
    std::array<std::vector<Band>, 2> fam;
    for (std::size_t k = 0; k < passes.size(); ++k) {
      const std::vector<Vec3>& p = passes[k];
      for (std::size_t i = 1; i < p.size(); ++i) {
        const double fa = spine ? t0.dot(p[i - 1] - c0) : coord[k][i - 1] - x;
        const double fb = spine ? t0.dot(p[i] - c0) : coord[k][i] - x;
        if (!((fa < 0.0 && fb >= 0.0) || (fa >= 0.0 && fb < 0.0))) continue;
        const double t = fa / (fa - fb);
        const Vec3 q = p[i - 1] + t * (p[i] - p[i - 1]);
        if (spine && (q - c0).norm() > reach) continue;
        const Vec3 dir = (p[i] - p[i - 1]).normalized();
        Vec3 tau = Vec3::UnitX();
        Band b;
        b.u = locate(loop, q, &tau);
        b.sin = std::max(1e-3, dir.cross(tau).norm());
        b.trace = B / b.sin;
        fam[fb > fa ? 0 : 1].push_back(b);  // running up the station coordinate, or back
      }
    }
    StationCoverage st;
    st.station = x;
    st.loop_length = loop.length;
    const double L = loop.length;
    std::vector<double> spacing;
    double band_len = 0.0;
    st.cover_factor = std::numeric_limits<double>::infinity();
    for (int f = 0; f < 2; ++f) {
      std::vector<Band>& bands = fam[f];
      st.bands[f] = static_cast<int>(bands.size());
      const Sweep s = sweep(bands, L);
      st.family_bare[f] = s.bare / L;
      st.widest_gap = std::max(st.widest_gap, s.widest_gap);
      st.max_stack = std::max(st.max_stack, s.max_stack);
      double len = 0.0;
      for (const Band& b : bands) len += b.trace;
      band_len += len;
      st.cover_factor = std::min(st.cover_factor, len / L);
      std::sort(bands.begin(), bands.end(), [](const Band& a, const Band& b) { return a.u < b.u; });
      for (std::size_t i = 0; i < bands.size() && bands.size() > 1; ++i) {
        const Band& a = bands[i];
        const Band& b = bands[(i + 1) % bands.size()];
        double gap = b.u - a.u;
        if (gap < 0.0) gap += L;
        const double sin = 0.5 * (a.sin + b.sin);
        st.widest_overlap = std::max(st.widest_overlap, (0.5 * (a.trace + b.trace) - gap) * sin);
        spacing.push_back(gap * sin);
      }
    }
    st.bare_fraction = std::max(st.family_bare[0], st.family_bare[1]);
    st.mean_plies = band_len / L;
    st.spacing_cv = cv(spacing);
    for (double g : spacing) st.spacing_mean += g / spacing.size();
    rep.bare_fraction = std::max(rep.bare_fraction, st.bare_fraction);
    rep.widest_gap = std::max(rep.widest_gap, st.widest_gap);
    rep.widest_overlap = std::max(rep.widest_overlap, st.widest_overlap);
    rep.max_stack = std::max(rep.max_stack, st.max_stack);
    rep.cover_factor = std::min(rep.cover_factor, st.cover_factor);
    rep.spacing_cv = std::max(rep.spacing_cv, st.spacing_cv);
    plies_sum += st.mean_plies;
    rep.spacing_mean += st.spacing_mean;
    rep.stations.push_back(st);
  }
  double longest = 0.0;
  for (const StationCoverage& st : rep.stations) longest = std::max(longest, st.loop_length);
  for (const StationCoverage& st : rep.stations) {
    if (st.loop_length >= 0.995 * longest) {
      rep.widest_overlap_largest = std::max(rep.widest_overlap_largest, st.widest_overlap);
    }
  }
  if (rep.stations.empty()) {
    rep.cover_factor = 0.0;
  } else {
    rep.mean_plies = plies_sum / rep.stations.size();
    rep.spacing_mean /= rep.stations.size();
  }
  return rep;
}

}  // namespace windplan
