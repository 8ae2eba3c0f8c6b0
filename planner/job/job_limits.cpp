#include "planner/job/job_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

std::string num(double v) {
  char buf[32];
  if (v == std::floor(v) && std::fabs(v) < 1e7) {
    std::snprintf(buf, sizeof buf, "%.0f", v + 0.0);  // whole numbers as such: 10000, not 1e+04
  } else {
    std::snprintf(buf, sizeof buf, "%.4g", v + 0.0);
  }
  return buf;
}

// "file:line" of a dotted key path ("winding.meridians", "mandrel.bent_tube.bends[1].radius"),
// or the file alone when a part is absent (a default value).
std::string where_key(const ConfigNode& root, const std::string& dotted) {
  YAML::Node n = root.yaml();
  YAML::Mark mark = n.Mark();
  std::size_t pos = 0;
  bool found = true;
  while (found && pos < dotted.size()) {
    std::size_t end = dotted.find_first_of(".[", pos);
    if (end == std::string::npos) end = dotted.size();
    const std::string part = dotted.substr(pos, end - pos);
    found = false;
    if (n.IsMap()) {
      for (auto it = n.begin(); it != n.end(); ++it) {
        if (it->first.IsScalar() && it->first.Scalar() == part) {
          mark = it->first.Mark();
          n = it->second;
          found = true;
          break;
        }
      }
    }
    pos = end;
    while (found && pos < dotted.size() && dotted[pos] == '[') {
      const std::size_t close = dotted.find(']', pos);
      const std::size_t i = std::stoul(dotted.substr(pos + 1, close - pos - 1));
      found = n.IsSequence() && i < n.size();
      if (found) {
        n = n[i];
        mark = n.Mark();
      }
      pos = close + 1;
    }
    if (pos < dotted.size() && dotted[pos] == '.') ++pos;
  }
  if (!found || mark.is_null() || mark.line < 0) return root.file();
  return root.file() + ":" + std::to_string(mark.line + 1);
}

class Checker {
 public:
  Checker(const ConfigNode& root, const JobLimits& l) : root_(root), l_(l) {}

  [[noreturn]] void fail(const std::string& key, double value, const std::string& unit,
                         const std::string& bound) const {
    throw ConfigError(where_key(root_, key) + ": key '" + key + "' = " + num(value) + unit + " " +
                      bound);
  }
  /// A length in [min_length, max_length] (or 0 when zero_ok).
  void length(const std::string& key, double v, bool zero_ok = false) const {
    if (zero_ok && v == 0.0) return;
    if (std::fabs(v) < l_.min_length) {
      fail(key, v, " mm", "is below the bound " + num(l_.min_length) + " mm (1 um)");
    }
    if (std::fabs(v) > l_.max_length) {
      fail(key, v, " mm", "exceeds the bound " + num(l_.max_length) + " mm (100 m)");
    }
  }
  /// A coordinate (may be 0 or negative): |v| <= max_length.
  void coordinate(const std::string& key, double v) const {
    if (std::isfinite(v) && std::fabs(v) > l_.max_length) {
      fail(key, v, " mm", "exceeds the bound +-" + num(l_.max_length) + " mm (100 m)");
    }
  }
  void count(const std::string& key, double v, double bound, const std::string& what) const {
    if (v > bound) fail(key, v, "", "exceeds the bound " + num(bound) + " (" + what + ")");
  }

 private:
  const ConfigNode& root_;
  const JobLimits& l_;
};

// Tessellation edge length for deflections `t` on curvature radius r (see the header).
double tessellation_edge(double r, const TessellateOptions& t) {
  const double by_chord = std::sqrt(8.0 * r * t.linear_deflection);
  const double by_angle = r * t.angular_deflection * M_PI / 180.0;
  return std::max(1e-300, std::min(by_chord, by_angle));
}

constexpr double kTriangleArea = 0.433;  // sqrt(3) / 4: an equilateral triangle of edge 1

// An implausible combination: the key to name, its value and unit, and the rest of the message
// ("" key: plausible).
struct Finding {
  std::string key;
  double value = 0.0;
  std::string unit;
  std::string text;
};

// The winding angle alpha (rad, from the axis) of the passes on the largest radius R and the key
// that sets it ("" for a vessel's default turnaround); NaN when unknown (a mesh or CAD mandrel
// whose turns are not given: its passes turn around on domes the planner finds).
double winding_angle(const Job& job, const WindingOptions& w, double r, double l,
                     std::string* key) {
  const std::string& src = job.mandrel.source;
  if (!std::isnan(w.angle)) {
    *key = "winding.angle";
    return w.angle * M_PI / 180.0;
  }
  if (std::isfinite(w.turnaround)) {
    *key = "winding.turnaround";
    return std::asin(std::min(1.0, w.turnaround / r));
  }
  const bool parametric_no_domes =
      src == "pipe" || src == "cone" || src == "bent_tube" || src == "section";
  if (w.turns_given || parametric_no_domes) {
    *key = "winding.turns";
    return std::atan2(2.0 * M_PI * r * w.turns, l);
  }
  if (src == "vessel") {  // the planner's default: c = the larger polar opening + half the band
    key->clear();
    const double c = std::max(job.mandrel.vessel.dome_start.polar_opening,
                              job.mandrel.vessel.dome_end.polar_opening) +
                     0.5 * w.band_width;
    return std::asin(std::min(1.0, c / r));
  }
  return std::nan("");
}

bool finite_travel(const AxisOptions& a) { return std::isfinite(a.min) && std::isfinite(a.max); }

Finding find_implausible(const Job& job, const WindingOptions& w, double r, double l,
                         const JobLimits& lim) {
  const MachineOptions& mc = job.machine;
  const EnvelopeOptions& env = mc.envelope;
  const bool lathe = mc.kind == "lathe2" || mc.kind == "lathe4";
  const std::string mode = env.mode();
  // The eye grazes the mandrel (a 1 um clearance).
  if (mode == "clearance" && env.clearance < lim.min_clearance_chords * mc.chord_tolerance) {
    return {"machine.envelope.clearance", env.clearance, " mm",
            "is within " + num(lim.min_clearance_chords) +
                " chord tolerances (machine.chord_tolerance = " + num(mc.chord_tolerance) +
                " mm) of the mandrel: the resampled eye and fibre paths each stray by up to a "
                "chord tolerance, so the eye would graze the mandrel and the replay lay the "
                "fibre elsewhere; use a clearance >= " +
                num(lim.min_clearance_chords * mc.chord_tolerance) +
                " mm or a smaller chord_tolerance"};
  }
  if (!(r > 0.0) || !(l > 0.0)) return {};
  // A mesh or CAD mandrel longer than the carriage travels (a mesh in mm read as inches; a
  // parametric mandrel's length is typed in mm, and may be wound in part between stations).
  const bool from_file = job.mandrel.source == "mesh" || job.mandrel.source == "cad";
  if (from_file && lathe && finite_travel(mc.x) && l > mc.x.max - mc.x.min) {
    return {"machine.axes.X", mc.x.max - mc.x.min, " mm",
            "of travel (" + num(mc.x.min) + " to " + num(mc.x.max) +
                " mm) is shorter than the mandrel, " + num(l) +
                " mm along the axis: check mandrel.units (a mesh in mm read as inches is 25.4 "
                "times too large) or the machine profile"};
  }
  std::string angle_key;
  const double alpha = winding_angle(job, w, r, l, &angle_key);
  // The fibre laid: 2 K passes.
  const double circumference = 2.0 * M_PI * r;
  const double k = w.circuits > 0 ? w.circuits : std::ceil(circumference / w.band_width);
  double pass = l;
  if (angle_key == "winding.turns") {
    pass = std::hypot(circumference * w.turns, l);
  } else if (std::isfinite(alpha) && std::cos(alpha) > 1e-3) {
    pass = l / std::cos(alpha);
  }
  const double fibre = 2.0 * k * pass;
  if (fibre > lim.max_fibre_length) {
    const bool auto_k = w.circuits == 0;
    return {auto_k ? "winding.band_width" : "winding.circuits",
            auto_k ? w.band_width : double(w.circuits), auto_k ? " mm" : "",
            "makes the plan lay about " + num(fibre / 1e6) + " km of fibre (" + num(k) +
                " circuits of two " + num(pass / 1e3) + " m passes on a mandrel of radius " +
                num(r) + " mm, " + num(l) + " mm long), above the bound " +
                num(lim.max_fibre_length / 1e6) +
                " km: check mandrel.units (a mesh in mm read as inches is 25.4 times too large), "
                "or use a wider band"};
  }
  if (!std::isfinite(alpha) || !(alpha > 0.0)) return {};
  // The payout eye's lead along the axis behind the fibre's contact.
  double c = std::nan("");
  std::string c_key = "machine.envelope.clearance";
  double c_value = env.clearance;
  if (mode == "clearance") {
    c = env.radius > 0.0 && mc.kind == "lathe2" ? env.radius - r : env.clearance;
    if (env.radius > 0.0 && mc.kind == "lathe2") {
      c_key = "machine.envelope.radius";
      c_value = env.radius;
    }
  }
  double lead = std::nan("");
  if (mode == "free_length") {
    lead = env.free_length * std::cos(alpha);
    c_key = "machine.envelope.free_length";
    c_value = env.free_length;
  } else if (c > 0.0) {
    lead = std::sqrt(c * (2.0 * r + c)) / std::tan(alpha);
  }
  const bool x_travel = lathe && finite_travel(mc.x);
  const double max_lead = x_travel
                              ? mc.x.max - mc.x.min
                              : std::max(lim.max_relative_eye_lead * l, lim.min_eye_lead_bound);
  if (lead > max_lead) {
    const std::string why =
        "the payout eye trails the fibre's contact by about " + num(lead) +
        " mm along the axis (winding angle " + num(alpha * 180.0 / M_PI) + " deg on radius " +
        num(r) + " mm, eye " +
        (mode == "free_length" ? num(env.free_length) + " mm along the fibre"
                               : num(c) + " mm out") +
        "), beyond " +
        (x_travel ? "the X axis travel, " + num(max_lead) + " mm"
                  : "the bound " + num(max_lead) + " mm (" +
                        (max_lead > lim.min_eye_lead_bound
                             ? num(lim.max_relative_eye_lead) + " times the mandrel's length, " +
                                   num(l) + " mm)"
                             : std::string("the least bound, for mandrels under ") +
                                   num(lim.min_eye_lead_bound / lim.max_relative_eye_lead) +
                                   " mm long)"));
    if (alpha < 10.0 * M_PI / 180.0 && !angle_key.empty()) {
      const double v = angle_key == "winding.turns"   ? w.turns
                       : angle_key == "winding.angle" ? w.angle
                                                      : w.turnaround;
      const std::string unit = angle_key == "winding.turns"   ? ""
                               : angle_key == "winding.angle" ? " deg"
                                                              : " mm";
      return {angle_key, v, unit,
              "on a mandrel " + num(l) + " mm long lays the fibre almost along the axis: " + why +
                  "; use more turns (a steeper winding angle)"};
    }
    return {c_key, c_value, " mm", "is too far out: " + why + "; use a smaller clearance"};
  }
  // The eye beyond the cross-feed's reach (lathe4: Y is the eye's radius).
  if (mc.kind == "lathe4" && mode == "clearance" && std::isfinite(mc.y.max) && r + c > mc.y.max) {
    return {c_key, c_value, " mm",
            "puts the payout eye at radius " + num(r + c) + " mm (mandrel radius " + num(r) +
                " mm), beyond the Y axis travel (max " + num(mc.y.max) +
                " mm): use a smaller clearance, or check mandrel.units"};
  }
  return {};
}

// find_implausible for `w`, then for each helical entry of the job's `layers:` (its keys named
// "layers[k].key"): every layer the job winds is held to the same bounds.
Finding find_implausible_with_layers(const Job& job, const WindingOptions& w, double r, double l,
                                     const JobLimits& lim) {
  Finding f = find_implausible(job, w, r, l, lim);
  for (std::size_t k = 0; f.key.empty() && k < job.layers.size(); ++k) {
    if (job.layers[k].kind != LayerKind::Helical) continue;
    f = find_implausible(job, job.layers[k].winding, r, l, lim);
    const std::string prefix = "winding.";
    if (f.key.rfind(prefix, 0) == 0) {
      f.key = "layers[" + std::to_string(k) + "]." + f.key.substr(prefix.size());
    }
  }
  return f;
}

}  // namespace

void check_plausibility(const Job& job, const WindingOptions& w, double radius, double axial,
                        const JobLimits& limits) {
  const Finding f = find_implausible_with_layers(job, w, radius, axial, limits);
  if (f.key.empty()) return;
  const std::string file = job.path.empty() ? std::string() : job.path.string() + ": ";
  throw ConfigError(file + "key '" + f.key + "' = " + num(f.value) + f.unit + " " + f.text);
}

namespace {

// The largest radius and the axial range of a mesh's vertices about the axis (mm).
struct MeshExtent {
  double radius, lo, hi;
};
MeshExtent mesh_extent(const Mesh& m, const SpindleAxis& axis) {
  MeshExtent e{0.0, INFINITY, -INFINITY};
  for (const Vec3& p : m.points()) {
    e.radius = std::max(e.radius, axis.radius(p));
    e.lo = std::min(e.lo, axis.axial(p));
    e.hi = std::max(e.hi, axis.axial(p));
  }
  return e;
}

}  // namespace

void check_plausibility(const Job& job, const Mesh& m, const SpindleAxis& axis,
                        const JobLimits& limits) {
  if (m.num_faces() == 0) return;
  const auto [radius, lo, hi] = mesh_extent(m, axis);
  check_plausibility(job, job.winding, radius, hi - lo, limits);
}

MandrelSize parametric_mandrel_size(const MandrelOptions& m) {
  MandrelSize s;
  if (m.source == "pipe") {
    s.radius = m.pipe.radius;
    s.axial = m.pipe.length;
    s.area = 2.0 * M_PI * s.radius * s.axial;
    s.size = std::hypot(2.0 * s.radius, s.axial);
  } else if (m.source == "cone") {
    s.radius = std::max(m.cone.radius_start, m.cone.radius_end);
    s.axial = m.cone.length;
    s.area = M_PI * (m.cone.radius_start + m.cone.radius_end) * s.axial;
    s.size = std::hypot(2.0 * s.radius, s.axial);
  } else if (m.source == "vessel") {
    const VesselParams& v = m.vessel;
    s.radius = v.radius;
    double domes = 0.0, heights = 0.0;
    for (const DomeParams& d : {v.dome_start, v.dome_end}) {
      const double h = d.type == DomeType::Elliptical ? d.aspect * v.radius : v.radius;
      heights += h;
      domes += 2.0 * M_PI * v.radius * std::max(v.radius, h);
    }
    s.axial = v.length + heights;
    s.area = 2.0 * M_PI * v.radius * v.length + domes;
    s.size = std::hypot(2.0 * s.radius, s.axial);
  } else if (m.source == "bent_tube") {
    const BentTubeParams& b = m.bent_tube;
    s.radius = b.radius;
    for (double seg : b.segments) s.axial += seg;
    for (const BendParams& bend : b.bends) s.axial += bend.radius * bend.angle * M_PI / 180.0;
    s.area = 2.0 * M_PI * b.radius * s.axial;
    s.size = s.axial + 2.0 * b.radius;
  }
  return s;
}

double estimate_tessellation_triangles(double area, double radius, const TessellateOptions& t) {
  const double l = tessellation_edge(radius, t);
  return area / (kTriangleArea * l * l);
}

void check_tessellation_size(const MandrelSize& s, const TessellateOptions& t,
                             const JobLimits& limits) {
  if (!(s.size > 0.0)) return;
  const double min_d = limits.min_relative_deflection * s.size;
  if (t.linear_deflection < min_d) {
    throw ConfigError("key 'mandrel.linear_deflection' = " + num(t.linear_deflection) +
                      " mm is below the bound " + num(min_d) + " mm (" +
                      num(limits.min_relative_deflection) + " of the mandrel's size, " +
                      num(s.size) + " mm)");
  }
  const double tri = estimate_tessellation_triangles(s.area, s.radius, t);
  if (tri > limits.max_triangles) {
    throw ConfigError("keys 'mandrel.linear_deflection' = " + num(t.linear_deflection) +
                      " mm, 'mandrel.angular_deflection' = " + num(t.angular_deflection) +
                      " deg: about " + num(tri) + " triangles on this mandrel (area " +
                      num(s.area) + " mm^2), above the bound " + num(limits.max_triangles) +
                      "; use larger deflections");
  }
}

void check_remesh_size(const MandrelSize& s, double remesh, const JobLimits& limits) {
  if (!(remesh > 0.0) || !(s.size > 0.0)) return;
  const double max_r = limits.max_relative_remesh * s.size;
  if (remesh > max_r) {
    throw ConfigError("key 'mandrel.remesh' = " + num(remesh) + " mm exceeds the bound " +
                      num(max_r) + " mm (" + num(limits.max_relative_remesh) +
                      " of the mandrel's size, " + num(s.size) +
                      " mm): such triangles cannot follow its shape");
  }
  const double tri = s.area / (kTriangleArea * remesh * remesh);
  if (tri > limits.max_triangles) {
    throw ConfigError("key 'mandrel.remesh' = " + num(remesh) + " mm gives about " + num(tri) +
                      " triangles on this mandrel (area " + num(s.area) +
                      " mm^2), above the bound " + num(limits.max_triangles) + "; use >= " +
                      num(std::sqrt(s.area / (kTriangleArea * limits.max_triangles))) + " mm");
  }
}

void check_mandrel_extent(const MandrelSize& s, const std::string& what, const JobLimits& limits) {
  if (s.size > limits.max_length) {
    throw ConfigError(what + " is " + num(s.size) + " mm across, above the bound " +
                      num(limits.max_length) + " mm (100 m): check mandrel.units");
  }
  if (s.size < limits.min_length) {
    throw ConfigError(what + " is " + num(s.size) + " mm across, below the bound " +
                      num(limits.min_length) + " mm (1 um): check mandrel.units");
  }
}

double estimate_plan_points(const WindingOptions& w, double radius, double axial, double edge) {
  const double circumference = 2.0 * M_PI * radius;
  const double k = w.circuits > 0 ? w.circuits : std::ceil(circumference / w.band_width);
  return 2.0 * k * 2.0 * (w.turns * circumference + axial) / std::max(edge, 1e-300);
}

void check_plan_size(const WindingOptions& w, double radius, double axial, double edge,
                     const JobLimits& limits) {
  const double circumference = 2.0 * M_PI * radius;
  if (w.band_width > circumference) {
    // Named up front (issue 28: found only by a late replay error).
    throw ConfigError("key 'winding.band_width' = " + num(w.band_width) +
                      " mm is wider than the mandrel's circumference, " + num(circumference) +
                      " mm at its largest radius " + num(radius) +
                      " mm: one band would lap over itself; check the band width and the "
                      "mandrel's units");
  }
  if (w.circuits == 0 && circumference / w.band_width > limits.max_circuits) {
    throw ConfigError("key 'winding.band_width' = " + num(w.band_width) + " mm gives about " +
                      num(circumference / w.band_width) + " circuits on a circumference of " +
                      num(circumference) + " mm (circuits: auto), above the bound " +
                      num(limits.max_circuits) + "; use a wider band or give winding.circuits");
  }
  const double points = estimate_plan_points(w, radius, axial, edge);
  if (points > limits.max_plan_points) {
    throw ConfigError(
        "keys 'winding.turns' = " + num(w.turns) +
        ", 'winding.circuits' = " + (w.circuits > 0 ? num(w.circuits) : std::string("auto")) +
        ": about " + num(points) + " plan points on this mandrel (largest radius " + num(radius) +
        " mm, mean edge " + num(edge) + " mm), above the bound " + num(limits.max_plan_points) +
        "; use fewer turns or circuits, or a coarser mesh");
  }
}

void check_plan_size(const WindingOptions& w, const Mesh& m, const SpindleAxis& axis,
                     const JobLimits& limits) {
  if (m.num_faces() == 0) return;
  const auto [radius, lo, hi] = mesh_extent(m, axis);
  const double edge = std::sqrt(m.total_area() / (kTriangleArea * m.num_faces()));
  check_plan_size(w, radius, hi - lo, edge, limits);
}

void check_job_limits(const Job& job, const ConfigNode& root, const JobLimits& l) {
  const Checker c(root, l);
  const MandrelOptions& m = job.mandrel;
  // Dimensions.
  c.length("mandrel.linear_deflection", m.tessellation.linear_deflection);
  c.length("mandrel.remesh", m.remesh, true);
  c.coordinate("mandrel.axis.origin", m.axis.origin.cwiseAbs().maxCoeff());
  if (m.source == "pipe") {
    c.length("mandrel.pipe.radius", m.pipe.radius);
    c.length("mandrel.pipe.length", m.pipe.length);
  } else if (m.source == "cone") {
    c.length("mandrel.cone.radius_start", m.cone.radius_start);
    c.length("mandrel.cone.radius_end", m.cone.radius_end);
    c.length("mandrel.cone.length", m.cone.length);
  } else if (m.source == "vessel") {
    c.length("mandrel.vessel.radius", m.vessel.radius);
    c.length("mandrel.vessel.length", m.vessel.length, true);
    // (`dome:` sets both domes; a dome_start/dome_end section overrides it.)
    const YAML::Node vy = root.yaml()["mandrel"]["vessel"];
    for (const auto& [key, d] :
         {std::pair<std::string, DomeParams>{"dome_start", m.vessel.dome_start},
          std::pair<std::string, DomeParams>{"dome_end", m.vessel.dome_end}}) {
      const std::string k = vy.IsMap() && vy[key] ? key : std::string("dome");
      c.length("mandrel.vessel." + k + ".polar_opening", d.polar_opening);
    }
  } else if (m.source == "bent_tube") {
    const BentTubeParams& b = m.bent_tube;
    c.length("mandrel.bent_tube.radius", b.radius);
    c.count("mandrel.bent_tube.segments", double(b.segments.size()), l.max_segments,
            "straight segments");
    for (std::size_t i = 0; i < b.segments.size(); ++i) {
      c.length("mandrel.bent_tube.segments", b.segments[i], true);
    }
    for (std::size_t i = 0; i < b.bends.size(); ++i) {
      c.length("mandrel.bent_tube.bends[" + std::to_string(i) + "].radius", b.bends[i].radius);
    }
  }
  // Counts.
  const WindingOptions& w = job.winding;
  c.count("winding.meridians", w.meridians, l.max_meridians, "meridians sampled per turn");
  c.count("winding.circuits", w.circuits, l.max_circuits, "circuits");
  c.count("winding.turns", w.turns, l.max_turns, "turns per pass");
  c.length("winding.band_width", w.band_width);
  c.length("winding.curvature_window", w.curvature_window, true);
  c.coordinate("winding.start_station", w.start_station);
  c.coordinate("winding.end_station", w.end_station);
  c.count("girth.samples", job.girth.samples, l.max_girth_samples, "exact girth evaluations");
  c.count("girth.rings", job.girth.rings, l.max_girth_rings, "girth sample rings");
  c.count("cutlines", double(job.cutlines.size()), l.max_cutlines, "cut-lines");
  // Machine lengths.
  const MachineOptions& mc = job.machine;
  c.length("machine.chord_tolerance", mc.chord_tolerance);
  c.length("machine.envelope.clearance", mc.envelope.clearance);
  c.length("machine.envelope.free_length", mc.envelope.free_length, true);
  for (std::size_t i = 0; i < mc.envelope.profile.size(); ++i) {
    c.coordinate(
        "machine.envelope.profile[" + std::to_string(i) + "]",
        std::max(std::fabs(mc.envelope.profile[i][0]), std::fabs(mc.envelope.profile[i][1])));
  }

  // Estimates, when the size is known from the parameters (the plausibility of a mesh or CAD
  // mandrel waits for its size; the clearance against the chord tolerance needs none).
  const MandrelSize s = parametric_mandrel_size(m);
  if (!(s.size > 0.0)) {
    const Finding f = find_implausible_with_layers(job, w, 0.0, 0.0, l);
    if (!f.key.empty()) c.fail(f.key, f.value, f.unit, f.text);
    return;
  }
  c.length("mandrel", s.size);  // (each dimension is bounded; their sum too)
  try {
    check_tessellation_size(s, m.tessellation, l);
    check_remesh_size(s, m.remesh, l);
  } catch (const ConfigError& e) {
    throw ConfigError(where_key(root, "mandrel") + ": " + e.what());
  }
  const double circumference = 2.0 * M_PI * s.radius;
  const double k_auto = circumference / w.band_width;
  if (w.band_width > circumference) {
    c.fail("winding.band_width", w.band_width, " mm",
           "is wider than the mandrel's circumference, " + num(circumference) +
               " mm at its largest radius " + num(s.radius) +
               " mm: one band would lap over itself; check the band width and the mandrel's "
               "size");
  }
  if (w.circuits == 0 && k_auto > l.max_circuits) {
    c.fail("winding.band_width", w.band_width, " mm",
           "gives about " + num(k_auto) + " circuits on a circumference of " + num(circumference) +
               " mm (circuits: auto), above the bound " + num(l.max_circuits));
  }
  const double edge = m.remesh > 0.0 ? m.remesh : tessellation_edge(s.radius, m.tessellation);
  const double points = estimate_plan_points(w, s.radius, s.axial, edge);
  if (points > l.max_plan_points) {
    const double k = w.circuits > 0 ? w.circuits : std::ceil(k_auto);
    c.fail("winding.turns", w.turns, "",
           "with " + num(k) + " circuits gives about " + num(points) +
               " plan points on this mandrel, above the bound " + num(l.max_plan_points) +
               "; use fewer turns or circuits, or a coarser mesh");
  }
  const Finding f = find_implausible_with_layers(job, w, s.radius, s.axial, l);
  if (!f.key.empty()) c.fail(f.key, f.value, f.unit, f.text);
}

}  // namespace windplan
