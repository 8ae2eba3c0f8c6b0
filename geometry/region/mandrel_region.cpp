#include "geometry/region/mandrel_region.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

std::string fmt(double v, int digits = 4) {
  std::ostringstream s;
  s << std::setprecision(digits) << (std::abs(v) < 5e-13 ? 0.0 : v);
  return s.str();
}

// Angle of p about the axis in a fixed frame (u, w) normal to it.
struct AxisFrame {
  SpindleAxis axis;
  Vec3 u, w;
  explicit AxisFrame(const SpindleAxis& a) : axis(a) {
    axis.direction.normalize();
    u = axis.direction.unitOrthogonal();
    w = axis.direction.cross(u);
  }
  Vec2 plane(const Vec3& p) const {
    const Vec3 x = p - axis.origin;
    return Vec2(x.dot(u), x.dot(w));
  }
};

// Winding number of a closed polygon about the axis (rounded; 0 when it passes through it).
int winding_number(const std::vector<Vec3>& loop, const AxisFrame& frame) {
  double total = 0.0;
  const int n = static_cast<int>(loop.size());
  for (int k = 0; k < n; ++k) {
    const Vec2 a = frame.plane(loop[k]), b = frame.plane(loop[(k + 1) % n]);
    if (a.norm() < 1e-12 || b.norm() < 1e-12) return 0;
    total += std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
  }
  return static_cast<int>(std::lround(total / (2.0 * M_PI)));
}

// `index` is scratch space of one -1 per mesh vertex; it is left all -1 again.
CandidateRegion describe_part(const Mesh& mesh, std::vector<int> faces, const AxisFrame& frame,
                              std::vector<int>& index) {
  CandidateRegion c;
  c.faces = static_cast<int>(faces.size());
  c.axial_min = c.radius_min = std::numeric_limits<double>::infinity();
  c.axial_max = c.radius_max = -c.axial_min;
  TriangleSoup soup;
  std::vector<int> used;
  for (int f : faces) {
    const double a = mesh.face_area(f);
    c.area += a;
    c.mean_radius += a * frame.axis.radius(mesh.face_centroid(f));
    Tri t = mesh.triangle(f);
    for (int& v : t) {
      if (index[v] < 0) {
        index[v] = static_cast<int>(soup.points.size());
        used.push_back(v);
        const Vec3& p = mesh.position(v);
        soup.points.push_back(p);
        c.axial_min = std::min(c.axial_min, frame.axis.axial(p));
        c.axial_max = std::max(c.axial_max, frame.axis.axial(p));
        c.radius_min = std::min(c.radius_min, frame.axis.radius(p));
        c.radius_max = std::max(c.radius_max, frame.axis.radius(p));
      }
      v = index[v];
    }
    soup.triangles.push_back(t);
  }
  for (int v : used) index[v] = -1;
  if (c.area > 0.0) c.mean_radius /= c.area;
  try {
    const Mesh part(std::move(soup));
    const auto loops = part.boundary_loops();
    c.loops = static_cast<int>(loops.size());
    c.genus = part.genus();
    for (const auto& L : loops) {
      std::vector<Vec3> pts;
      for (int v : part.loop_vertices(L)) pts.push_back(part.position(v));
      c.loops_around += std::abs(winding_number(pts, frame)) == 1;
    }
  } catch (const TopologyError&) {
    c.loops = -1;  // faces meeting at a vertex only: not a manifold patch
    c.genus = -1;
  }
  c.around = c.loops_around > 0;
  c.annulus = c.loops == 2 && c.loops_around == 2 && c.genus == 0;
  c.face_list = std::move(faces);
  return c;
}

}  // namespace

bool RegionOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!enabled) return true;
  if (centre_line) {
    if (!std::isfinite(from) || !std::isfinite(to)) {
      return fail("region.centre_line: from and to must be finite");
    }
    if ((from_fraction && !(from >= 0.0 && from <= 1.0)) ||
        (to_fraction && !(to >= 0.0 && to <= 1.0))) {
      return fail("region.centre_line: from_fraction and to_fraction must lie in [0, 1]");
    }
    if (from_fraction == to_fraction && !(from < to)) {
      return fail("region.centre_line: from (" + fmt(from) + ") must be smaller than to (" +
                  fmt(to) + ")");
    }
    if (surface != "outer") {
      return fail("region.surface: " + surface + " is not supported with region.centre_line " +
                  "(it takes the largest annulus, or region.component)");
    }
    if (component < 0) return fail("region.component must be >= 1 (0 = the largest annulus)");
    std::string w;
    if (!cut.is_valid(&w)) return fail("region: " + w);
    return true;
  }
  if (!std::isfinite(start) || !std::isfinite(end)) {
    return fail("region.start and region.end must be finite (mm)");
  }
  if (!(start < end)) {
    return fail("region.start (" + fmt(start) + " mm) must be smaller than region.end (" +
                fmt(end) + " mm)");
  }
  if (surface != "outer" && surface != "inner") {
    return fail("region.surface must be outer or inner (got '" + surface + "')");
  }
  if (component < 0) return fail("region.component must be >= 1 (0 = choose by surface)");
  std::string w;
  if (!cut.is_valid(&w)) return fail("region: " + w);
  return true;
}

std::string CandidateRegion::brief() const {
  std::ostringstream s;
  s << "#" << index << ": axial " << fmt(axial_min) << ".." << fmt(axial_max) << " mm, radius "
    << fmt(radius_min) << ".." << fmt(radius_max) << " mm, ";
  if (loops < 0) {
    s << "not a manifold patch";
  } else {
    s << loops << " loop(s) (" << loops_around << " around the axis), genus " << genus;
  }
  s << ", " << fmt(area, 6) << " mm^2" << (annulus ? ", annulus" : "");
  return s.str();
}

std::vector<CandidateRegion> candidate_regions(const Mesh& mesh, const std::vector<char>& select,
                                               const SpindleAxis& axis) {
  if (static_cast<int>(select.size()) != mesh.num_faces()) {
    throw InputError("candidate regions: face selection has " + std::to_string(select.size()) +
                     " flags for " + std::to_string(mesh.num_faces()) + " faces");
  }
  const AxisFrame frame(axis);
  std::vector<int> comp(mesh.num_faces(), -1);
  std::vector<int> scratch(mesh.num_vertices(), -1);
  std::vector<CandidateRegion> out;
  for (int seed = 0; seed < mesh.num_faces(); ++seed) {
    if (!select[seed] || comp[seed] >= 0) continue;
    const int id = static_cast<int>(out.size());
    std::vector<int> faces{seed}, stack{seed};
    comp[seed] = id;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int g = mesh.face(mesh.twin(3 * f + k));
        if (g >= 0 && select[g] && comp[g] < 0) {
          comp[g] = id;
          faces.push_back(g);
          stack.push_back(g);
        }
      }
    }
    out.push_back(describe_part(mesh, std::move(faces), frame, scratch));
  }
  std::stable_sort(out.begin(), out.end(), [](const CandidateRegion& a, const CandidateRegion& b) {
    return a.area > b.area;
  });
  for (std::size_t i = 0; i < out.size(); ++i) out[i].index = static_cast<int>(i) + 1;
  return out;
}

std::string region_table(const std::vector<CandidateRegion>& regions, const std::string& indent) {
  std::ostringstream s;
  s << indent << "  #   faces   axial min..max (mm)     radius min..max (mm)   loops  around  genus"
    << "   area (mm^2)\n";
  for (const CandidateRegion& c : regions) {
    s << indent << std::setw(3) << c.index << std::setw(8) << c.faces << "   " << std::setw(9)
      << fmt(c.axial_min, 6) << " .. " << std::left << std::setw(9) << fmt(c.axial_max, 6)
      << std::right << "  " << std::setw(9) << fmt(c.radius_min, 6) << " .. " << std::left
      << std::setw(9) << fmt(c.radius_max, 6) << std::right << std::setw(6) << c.loops
      << std::setw(8) << c.loops_around << std::setw(7) << c.genus << "   " << fmt(c.area, 8)
      << (c.annulus ? "  annulus" : "") << "\n";
  }
  return s.str();
}

std::string RegionSuggestion::keys() const {
  if (!found) return "";
  std::ostringstream s;
  s << "region: {start: " << fmt(start, 8) << ", end: " << fmt(end, 8) << "}";
  return s.str();
}

namespace {

RegionSelection select_region_impl(const Mesh& full, const SpindleAxis& axis,
                                   const RegionOptions& options, bool suggest) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("mandrel." + why);
  const double a = options.start, b = options.end;
  const std::string range = "[" + fmt(a, 8) + ", " + fmt(b, 8) + "] mm";
  double amin = std::numeric_limits<double>::infinity(), amax = -amin;
  for (const Vec3& p : full.points()) {
    amin = std::min(amin, axis.axial(p));
    amax = std::max(amax, axis.axial(p));
  }
  const std::string extent = "[" + fmt(amin, 8) + ", " + fmt(amax, 8) + "] mm";
  if (!(b > amin && a < amax)) {
    throw ConfigError("mandrel.region: the range " + range +
                      " misses the mandrel, whose axial extent along the spindle axis is " +
                      extent + "; set region.start and region.end inside it");
  }
  PlaneCutResult cut = cut_at_stations(full, axis, {a, b}, options.cut);
  RegionSelection out;
  out.split_edges = cut.split_edges;
  out.split_faces = cut.split_faces;
  out.moved_vertices = cut.moved_vertices;
  out.max_move = cut.max_move;
  out.face_parent = std::move(cut.face_parent);
  out.mesh = std::move(cut.mesh);
  const Mesh& m = out.mesh;
  // No face straddles a plane now: a face is inside when its centroid is strictly between them
  // (faces lying in a plane, e.g. a flange face exactly at a station, are not).
  const double eps = 1e-9 * std::max(1.0, m.bounding_box().diagonal_length());
  std::vector<char> inside(m.num_faces(), 0);
  for (int f = 0; f < m.num_faces(); ++f) {
    const double x = axis.axial(m.face_centroid(f));
    inside[f] = x > a + eps && x < b - eps;
  }
  out.candidates = candidate_regions(m, inside, axis);
  auto listing = [&]() {
    std::string s;
    for (const CandidateRegion& c : out.candidates) s += (s.empty() ? "" : "; ") + c.brief();
    return s;
  };
  if (out.candidates.empty()) {
    throw ConfigError("mandrel.region: the range " + range + " holds no surface of the mandrel " +
                      "(axial extent " + extent + ")");
  }
  auto suggestion = [&]() {
    if (!suggest) return std::string();
    const RegionSuggestion s = suggest_region(full, axis);
    return s.found ? "; suggested: " + s.keys() : std::string();
  };
  if (options.component > 0) {
    if (options.component > static_cast<int>(out.candidates.size())) {
      throw ConfigError("mandrel.region.component: " + std::to_string(options.component) +
                        " is out of range: the range " + range + " holds " +
                        std::to_string(out.candidates.size()) + " candidate(s): " + listing());
    }
    out.chosen = options.component - 1;
  } else {
    std::vector<int> around;
    for (std::size_t i = 0; i < out.candidates.size(); ++i) {
      if (out.candidates[i].around) around.push_back(static_cast<int>(i));
    }
    if (around.empty()) {
      const bool closed = std::any_of(out.candidates.begin(), out.candidates.end(),
                                      [](const CandidateRegion& c) { return c.loops == 0; });
      throw ConfigError(
          "mandrel.region: no surface in the range " + range + " goes around the spindle axis (" +
          (closed ? "the range takes in a closed part of the mandrel: keep region.start and "
                    "region.end inside its axial extent " +
                        extent + " to cut it open"
                  : "check mandrel.axis and the range") +
          "); candidates: " + listing() + suggestion());
    }
    const bool outer = options.surface == "outer";
    int pick = around[0];
    for (int i : around) {
      const double r = out.candidates[i].mean_radius, best = out.candidates[pick].mean_radius;
      if (outer ? r > best : r < best) pick = i;
    }
    // Surfaces around the axis nest (a wall and its bore) when their axial extents overlap; two
    // that follow each other along the axis are both candidates for the outer surface.
    for (int i : around) {
      const CandidateRegion &p = out.candidates[pick], &c = out.candidates[i];
      const double overlap =
          std::min(p.axial_max, c.axial_max) - std::max(p.axial_min, c.axial_min);
      const double shorter = std::min(p.axial_max - p.axial_min, c.axial_max - c.axial_min);
      if (i != pick && overlap < 0.5 * shorter) {
        throw ConfigError("mandrel.region: the range " + range + " holds " +
                          std::to_string(around.size()) +
                          " surfaces around the axis that follow each other along it; choose " +
                          "one with mandrel.region.component (1-based): " + listing());
      }
    }
    out.chosen = pick;
  }
  const CandidateRegion& c = out.candidates[out.chosen];
  if (!c.annulus) {
    throw ConfigError("mandrel.region: surface #" + std::to_string(c.index) + " in the range " +
                      range + " is not an annulus (" + std::to_string(c.loops) + " loop(s), " +
                      std::to_string(c.loops_around) + " around the axis, genus " +
                      std::to_string(c.genus) + "): " +
                      (a < amin || b > amax
                           ? "the range runs past an end of the mandrel (axial extent " + extent +
                                 "); keep region.start/region.end inside it"
                           : std::string("flanges, holes or tabs in the range? narrow "
                                         "region.start/region.end")) +
                      "; " + "candidates: " + listing() + suggestion());
  }
  out.keep.assign(m.num_faces(), 0);
  for (int f : c.face_list) out.keep[f] = 1;
  return out;
}

}  // namespace

RegionSelection select_region(const Mesh& full, const SpindleAxis& axis,
                              const RegionOptions& options) {
  return select_region_impl(full, axis, options, true);
}

RegionSuggestion suggest_region(const Mesh& full, const SpindleAxis& axis_in, int stations) {
  RegionSuggestion out;
  if (full.num_faces() == 0) return out;
  const AxisFrame frame(axis_in);
  const SpindleAxis& axis = frame.axis;
  double amin = std::numeric_limits<double>::infinity(), amax = -amin, rmax = 0.0;
  for (const Vec3& p : full.points()) {
    amin = std::min(amin, axis.axial(p));
    amax = std::max(amax, axis.axial(p));
    rmax = std::max(rmax, axis.radius(p));
  }
  const int N = std::max(stations, 8);
  if (!(amax > amin) || !(rmax > 0.0)) return out;
  const double h = (amax - amin) / N;
  // Per station i (at amin + (i + 0.5) h) and ray k: sheets crossed and the outermost radius.
  const int K = 48;
  const double phase = 0.01234567;  // rays off the round angles a model's vertices sit at
  std::vector<int> sheets(static_cast<std::size_t>(N) * K, 0);
  std::vector<double> outer(sheets.size(), 0.0);
  for (int f = 0; f < full.num_faces(); ++f) {
    const Tri& t = full.triangle(f);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int v : t) {
      lo = std::min(lo, axis.axial(full.position(v)));
      hi = std::max(hi, axis.axial(full.position(v)));
    }
    const int i0 = std::max(0, static_cast<int>(std::ceil((lo - amin) / h - 0.5)));
    const int i1 = std::min(N - 1, static_cast<int>(std::floor((hi - amin) / h - 0.5)));
    for (int i = i0; i <= i1; ++i) {
      const double s = amin + (i + 0.5) * h;
      // The face's segment in the plane.
      Vec2 seg[2];
      int n = 0;
      for (int k = 0; k < 3 && n < 2; ++k) {
        const Vec3 &p = full.position(t[k]), &q = full.position(t[(k + 1) % 3]);
        const double dp = axis.axial(p) - s, dq = axis.axial(q) - s;
        if ((dp < 0.0) == (dq < 0.0)) continue;
        seg[n++] = frame.plane(p + dp / (dp - dq) * (q - p));
      }
      if (n < 2) continue;
      // Rays from the axis at angles 2 pi k / K + phase that the segment crosses.
      for (int k = 0; k < K; ++k) {
        const double th = 2.0 * M_PI * k / K + phase;
        const Vec2 r(std::cos(th), std::sin(th));
        const Vec2 e = seg[1] - seg[0];
        const double den = r.x() * e.y() - r.y() * e.x();
        if (std::abs(den) < 1e-300) continue;
        // seg[0] + v e = lambda r
        const double v = (seg[0].x() * r.y() - seg[0].y() * r.x()) / den;
        if (v < 0.0 || v >= 1.0) continue;
        const double lambda = (seg[0] + v * e).dot(r);
        if (lambda <= 0.0) continue;
        const std::size_t c = static_cast<std::size_t>(i) * K + k;
        ++sheets[c];
        outer[c] = std::max(outer[c], lambda);
      }
    }
  }
  // Station i and i + 1 are alike when every ray crosses as many sheets, and the outermost ones
  // within 2% of the largest radius; a run's score is its length times its outer radius.
  auto alike = [&](int i) {
    for (int k = 0; k < K; ++k) {
      const std::size_t a = static_cast<std::size_t>(i) * K + k, b = a + K;
      if (sheets[a] != sheets[b] || sheets[a] == 0) return false;
      if (std::abs(outer[a] - outer[b]) > 0.02 * rmax) return false;
    }
    return true;
  };
  std::vector<std::pair<double, std::pair<int, int>>> runs;
  for (int i = 0; i < N - 1;) {
    if (!alike(i)) {
      ++i;
      continue;
    }
    int j = i;
    double rsum = 0.0;
    while (j < N - 1 && alike(j)) ++j;
    for (int q = i; q <= j; ++q) {
      for (int k = 0; k < K; ++k) rsum += outer[static_cast<std::size_t>(q) * K + k];
    }
    runs.push_back({(j - i) * h * rsum / ((j - i + 1) * K), {i, j}});
    i = j + 1;
  }
  std::sort(runs.begin(), runs.end(),
            [](const auto& x, const auto& y) { return x.first > y.first; });
  // A run stops where the outline turns steeply, also on a dome running into its opening. Past
  // the run the wall may go on (a dome) until a flat face across the axis (a cap, a shoulder, a
  // flange or tab face) or a change of sheets: slab i (between stations i and i + 1) is "flat"
  // when such a face reaches into it.
  std::vector<char> flat(N, 0);
  const double c1 = std::cos(M_PI / 180.0);
  for (int f = 0; f < full.num_faces(); ++f) {
    if (!(std::abs(full.face_normal(f).dot(axis.direction)) > c1)) continue;
    const double x = axis.axial(full.face_centroid(f));
    const int i = static_cast<int>(std::floor((x - amin) / h - 0.5));
    for (int k = std::max(0, i - 1); k <= std::min(N - 1, i + 1); ++k) flat[k] = 1;
  }
  auto same_sheets = [&](int i) {
    for (int k = 0; k < K; ++k) {
      const std::size_t a = static_cast<std::size_t>(i) * K + k;
      if (sheets[a] == 0 || sheets[a] != sheets[a + K]) return false;
    }
    return true;
  };
  auto extend = [&](int i, int step) {
    while (true) {
      const int slab = step > 0 ? i : i - 1;
      if (slab < 0 || slab >= N - 1 || flat[slab] || !same_sheets(slab)) return i;
      i += step;
    }
  };
  // Round inwards to a tenth of the station spacing's decade (0.1 mm for a spacing of 1 to
  // 10 mm) so that the keys read well.
  const double q = std::pow(10.0, std::floor(std::log10(h)) - 1.0);
  auto attempt = [&](int i, int j) {
    RegionOptions o;
    o.enabled = true;
    o.start = std::ceil((amin + (i + 0.5) * h) / q) * q;
    o.end = std::floor((amin + (j + 0.5) * h) / q) * q;
    if (!(o.end > o.start)) return false;
    try {
      const RegionSelection sel = select_region_impl(full, axis, o, false);
      out.found = true;
      out.start = o.start;
      out.end = o.end;
      out.radius = sel.candidates[sel.chosen].mean_radius;
      return true;
    } catch (const InputError&) {
      return false;
    }
  };
  for (std::size_t r = 0; r < std::min<std::size_t>(runs.size(), 3); ++r) {
    const int i = runs[r].second.first, j = runs[r].second.second;
    const int ie = extend(i, -1), je = extend(j, +1);
    if ((ie < i || je > j) && (attempt(ie, je) || attempt(ie, j) || attempt(i, je))) return out;
    for (int shrink = 0; shrink < 3 && i + shrink < j - shrink; ++shrink) {
      if (attempt(i + shrink, j - shrink)) return out;
    }
  }
  return out;
}

}  // namespace windplan
