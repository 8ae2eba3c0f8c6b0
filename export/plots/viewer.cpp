#include "export/plots/viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <tuple>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/base/json.h"

namespace windplan {

namespace embedded {
const char* three_js();          // build/export/embedded/three_js.cpp
const char* viewer_app_js();     // build/export/embedded/viewer_app_js.cpp
const char* viewer_joints_js();  // build/export/embedded/viewer_joints_js.cpp
}  // namespace embedded

bool ViewerOptions::is_valid(std::string* why) const {
  if (max_bytes < 2000000) {
    if (why) *why = "max_bytes must be at least 2000000 (the page's scripts take about 0.9 MB)";
    return false;
  }
  return true;
}

std::vector<int> circuit_layers(const WindingPlan& plan) {
  std::vector<int> out(plan.circuits.size(), 0);
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerSummary& s = plan.layers[l];
    for (int k = s.first_circuit; k < s.first_circuit + s.circuit_count; ++k)
      if (k >= 0 && k < static_cast<int>(out.size())) out[k] = static_cast<int>(l);
  }
  return out;
}

double circuit_band_width(const WindingPlan& plan, int k) {
  const std::vector<int> layers = circuit_layers(plan);
  if (k >= 0 && k < static_cast<int>(layers.size()) &&
      layers[k] < static_cast<int>(plan.layers.size()) && plan.layers[layers[k]].band_width > 0.0)
    return plan.layers[layers[k]].band_width;
  return plan.metrics.band_width;
}

std::string layer_label(const WindingPlan& plan, int l) {
  if (l < 0 || l >= static_cast<int>(plan.layers.size())) return "layer " + std::to_string(l);
  const LayerSummary& s = plan.layers[l];
  char buf[64];
  std::snprintf(buf, sizeof buf, " (%s, %.1f deg)", s.kind.c_str(), s.angle);
  return s.name + buf;
}

std::string base64(const unsigned char* data, std::size_t n) {
  static const char* const k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string o;
  o.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const std::uint32_t b0 = data[i], b1 = i + 1 < n ? data[i + 1] : 0,
                        b2 = i + 2 < n ? data[i + 2] : 0;
    const std::uint32_t w = (b0 << 16) | (b1 << 8) | b2;
    o += k[(w >> 18) & 63];
    o += k[(w >> 12) & 63];
    o += i + 1 < n ? k[(w >> 6) & 63] : '=';
    o += i + 2 < n ? k[w & 63] : '=';
  }
  return o;
}

namespace {

// Float32 / uint32 arrays as base64 of their little-endian bytes (the page reads them with typed
// arrays, which use the platform's order: little-endian on every WebGL platform in use).
std::string b64_f32(const std::vector<float>& v) {
  std::vector<unsigned char> bytes(v.size() * 4);
  for (std::size_t i = 0; i < v.size(); ++i) {
    std::uint32_t w;
    std::memcpy(&w, &v[i], 4);
    for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<unsigned char>(w >> (8 * b));
  }
  return base64(bytes.data(), bytes.size());
}

std::string b64_u32(const std::vector<std::uint32_t>& v) {
  std::vector<unsigned char> bytes(v.size() * 4);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<unsigned char>(v[i] >> (8 * b));
  return base64(bytes.data(), bytes.size());
}

std::string fmt(const char* f, double v) { return format_number(f, v); }

// The mandrel after vertex clustering on a grid of `cell` mm (cell <= 0: as is), in the axis
// frame: each cell's vertices merge into their mean, triangles that lose a corner are dropped.
struct PageMesh {
  std::vector<float> xyz;
  std::vector<std::uint32_t> tris;
};

PageMesh cluster_mesh(const Mesh& mesh, const AxisFrame& frame, double cell) {
  PageMesh out;
  const auto& pts = mesh.points();
  std::vector<Vec3> local(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3 q = pts[i] - frame.origin;
    local[i] = Vec3(q.dot(frame.d), q.dot(frame.u), q.dot(frame.v));
  }
  std::vector<std::uint32_t> remap(pts.size());
  std::vector<Vec3> merged;
  std::vector<int> count;
  if (cell <= 0.0) {
    for (std::size_t i = 0; i < pts.size(); ++i) remap[i] = static_cast<std::uint32_t>(i);
    merged = local;
    count.assign(pts.size(), 1);
  } else {
    std::map<std::tuple<long, long, long>, std::uint32_t> cells;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const auto key = std::make_tuple(std::lround(std::floor(local[i].x() / cell)),
                                       std::lround(std::floor(local[i].y() / cell)),
                                       std::lround(std::floor(local[i].z() / cell)));
      auto it = cells.find(key);
      if (it == cells.end()) {
        it = cells.emplace(key, static_cast<std::uint32_t>(merged.size())).first;
        merged.push_back(Vec3::Zero());
        count.push_back(0);
      }
      remap[i] = it->second;
      merged[it->second] += local[i];
      ++count[it->second];
    }
  }
  for (std::size_t i = 0; i < merged.size(); ++i) {
    const Vec3 p = merged[i] / std::max(1, count[i]);
    out.xyz.insert(out.xyz.end(), {float(p.x()), float(p.y()), float(p.z())});
  }
  for (const auto& t : mesh.triangles()) {
    const std::uint32_t a = remap[t[0]], b = remap[t[1]], c = remap[t[2]];
    if (a == b || b == c || a == c) continue;
    out.tris.insert(out.tris.end(), {a, b, c});
  }
  return out;
}

// Which dense points of a circuit stay at stride k: every k-th, the ends of every segment and of
// the circuit.
std::vector<int> kept_points(const Circuit& c, int k) {
  const int n = static_cast<int>(c.points.size());
  std::vector<char> keep(n, 0);
  for (int i = 0; i < n; i += k) keep[i] = 1;
  if (n > 0) keep[n - 1] = 1;
  for (const CircuitSegment& s : c.segments) {
    if (s.first >= 0 && s.first < n) keep[s.first] = 1;
    if (s.last >= 0 && s.last < n) keep[s.last] = 1;
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (keep[i]) out.push_back(i);
  return out;
}

void headline_json(JsonWriter& j, const WindingPlan& plan, const Motion& motion) {
  const PlanMetrics& m = plan.metrics;
  auto row = [&](const std::string& label, const std::string& value) {
    j.begin_array().value(label).value(value).end_array();
  };
  j.key("headline").begin_array();
  row("fibre length", fmt("%.1f mm", m.fibre_length));
  row("wind time", fmt("%.1f s", motion.wind_time));
  row("circuits", std::to_string(m.circuits) + " (coverage needs " +
                      std::to_string(m.circuits_for_coverage) + ")");
  row("band width", fmt("%.2f mm", m.band_width));
  row("cover factor", fmt("%.3f", m.cover_factor));
  if (!m.pattern.empty()) row("pattern", m.pattern);
  row("spacing CV", fmt("%.4f", m.spacing_cv));
  row("max slippage (passes)", fmt("%.4f", m.max_slippage) + fmt(" (mu %.2f", m.friction) +
                                   fmt(", %.2f%% above)", 100.0 * m.slip_fraction));
  if (m.turnarounds.length > 0.0) {
    row("turnarounds", fmt("max slippage %.4f", m.turnarounds.max_slippage) +
                           fmt(", %.1f mm above mu", m.turnarounds.slip_length) +
                           fmt(" (%.2f%%)", 100.0 * m.turnarounds.slip_fraction));
  }
  row("bridging", fmt("%.1f mm", m.bridging_length));
  if (std::isfinite(m.geodesic_turn_limit)) {
    row("geodesic limit",
        fmt("%.2f turns per pass", m.geodesic_turn_limit) + fmt(" (N = %.2f)", m.turns_per_pass));
  }
  j.end_array();
  // The measured coverage (planner/winding/coverage.h), when the plan carries it: its figures, then
  // one row per station.
  const CoverageReport& cov = m.coverage;
  if (cov.measured()) {
    j.key("coverage").begin_array();
    row("bare (worst station)",
        fmt("%.2f%%", 100.0 * cov.bare_fraction) + fmt(", widest gap %.1f mm", cov.widest_gap));
    row("widest overlap",
        fmt("%.2f mm", cov.widest_overlap) +
            fmt(" (%.2f mm on the largest sections)", cov.widest_overlap_largest));
    row("bands stacked", "up to " + std::to_string(cov.max_stack));
    row("cover factor", fmt("%.3f (smallest)", cov.cover_factor));
    row("plies", fmt("%.2f (mean)", cov.mean_plies));
    row("spacing CV", fmt("%.4f", cov.spacing_cv) + fmt(", mean %.2f mm", cov.spacing_mean));
    row("stations", std::to_string(cov.stations.size()) + " measured" +
                        (cov.skipped ? ", " + std::to_string(cov.skipped) + " skipped" : ""));
    // Stations: mm along the axis on shapes of revolution, else levels of the harmonic height.
    const bool levels = std::isnan(m.geodesic_turn_limit);
    for (const StationCoverage& st : cov.stations) {
      row(levels ? fmt("at h = %.3f", st.station) : fmt("at %.1f mm", st.station),
          fmt("bare %.2f%%", 100.0 * st.bare_fraction) + fmt(", gap %.1f mm", st.widest_gap) +
              fmt(", %.2f plies", st.mean_plies));
    }
    j.end_array();
  }
  j.key("warnings").begin_array();
  for (const std::string& w : m.warnings) j.value(w);
  j.end_array();
}

// The data block for one decimation (point stride k, state stride ks, mesh cell size).
struct PageData {
  std::string json;
  std::string joints_json;  ///< robot cells: the "windplan-joints" block (else empty)
  int points = 0, states = 0, triangles = 0;
};

// The joint panel's data (ViewerJoints) for the machine states kept on the page.
std::string joints_data(const Motion& motion, const ViewerJoints& joints,
                        const std::vector<int>& kept) {
  std::vector<float> st, vals;
  std::vector<std::uint32_t> rows;
  for (int i : kept) {
    st.push_back(float(motion.states[i].t_s));
    rows.push_back(static_cast<std::uint32_t>(i));
    vals.push_back(float(joints.time[i]));
    for (const JointSeries& js : joints.series) vals.push_back(float(js.values[i]));
  }
  JsonWriter j(0, 9);
  j.begin_object();
  j.field("format", "windplan-joints 1");
  j.field("arm", joints.arm);
  j.field("cycle_time", joints.time.empty() ? 0.0 : joints.time.back());
  j.key("names").begin_array();
  for (const JointSeries& js : joints.series) j.value(js.name);
  j.end_array();
  // Limits; a joint without them (E1) is shown over its range in the program.
  std::vector<double> lo, hi;
  j.key("limited").begin_array();
  for (const JointSeries& js : joints.series) {
    const bool limited = std::isfinite(js.min) && std::isfinite(js.max);
    j.value(limited);
    double a = limited ? js.min : 0.0, b = limited ? js.max : 0.0;
    if (!limited && !js.values.empty()) {
      a = *std::min_element(js.values.begin(), js.values.end());
      b = *std::max_element(js.values.begin(), js.values.end());
      if (!(b > a)) b = a + 1.0;
    }
    lo.push_back(a);
    hi.push_back(b);
  }
  j.end_array();
  j.key("min").begin_array();
  for (double v : lo) j.value(v);
  j.end_array();
  j.key("max").begin_array();
  for (double v : hi) j.value(v);
  j.end_array();
  j.field("state_t", b64_f32(st));
  j.field("rows", b64_u32(rows));
  j.field("values", b64_f32(vals));
  j.end_object();
  return j.str();
}

PageData page_data(const WindingPlan& plan, const Motion& motion, const AxisFrame& frame,
                   const PageMesh& mesh, int k, int ks, const std::string& note,
                   const ViewerJoints* joints) {
  auto local = [&](const Vec3& p) {
    const Vec3 q = p - frame.origin;
    return Vec3(q.dot(frame.d), q.dot(frame.u), q.dot(frame.v));
  };
  auto local_dir = [&](const Vec3& n) {
    return Vec3(n.dot(frame.d), n.dot(frame.u), n.dot(frame.v));
  };
  PageData out;
  JsonWriter j(0, 9);
  j.begin_object();
  j.field("format", "windplan-viewer 1");
  j.field("job", plan.job_name);
  j.field("band_width", plan.metrics.band_width);
  j.field("mu", plan.metrics.friction);
  j.field("wind_time", motion.wind_time);
  j.field("feed_unit", motion.inverse_time ? "1/min (G93)" : "units/min (G94)");
  j.field("note", note);
  headline_json(j, plan, motion);

  // Circuits: the kept dense points, and for every dense index the kept one at or before it (the
  // machine states point into the kept points).
  const std::vector<int> layers = circuit_layers(plan);
  std::vector<float> pos, nrm, ang, slip;
  std::vector<std::vector<int>> kept_index(plan.circuits.size());
  j.key("circuits").begin_array();
  for (std::size_t c = 0; c < plan.circuits.size(); ++c) {
    const Circuit& ci = plan.circuits[c];
    const std::vector<int> kept = kept_points(ci, k);
    const int first = static_cast<int>(ang.size());
    kept_index[c].assign(ci.points.size(), first);
    std::size_t q = 0;
    for (std::size_t i = 0; i < ci.points.size(); ++i) {
      while (q + 1 < kept.size() && kept[q + 1] <= static_cast<int>(i)) ++q;
      kept_index[c][i] = first + static_cast<int>(q);
    }
    for (int i : kept) {
      const FibrePoint& p = ci.points[i];
      const Vec3 x = local(p.position), n = local_dir(p.normal);
      pos.insert(pos.end(), {float(x.x()), float(x.y()), float(x.z())});
      nrm.insert(nrm.end(), {float(n.x()), float(n.y()), float(n.z())});
      ang.push_back(float(p.winding_angle));
      slip.push_back(float(p.slippage));
    }
    j.begin_object()
        .field("index", ci.index)
        .field("layer", layers[c])
        .field("width", circuit_band_width(plan, static_cast<int>(c)))
        .field("first", first)
        .field("count", static_cast<int>(kept.size()))
        .end_object();
  }
  j.end_array();
  j.key("layers").begin_array();
  for (std::size_t l = 0; l < plan.layers.size(); ++l)
    j.value(layer_label(plan, static_cast<int>(l)));
  j.end_array();
  out.points = static_cast<int>(ang.size());
  j.field("positions", b64_f32(pos));
  j.field("normals", b64_f32(nrm));
  j.field("angles", b64_f32(ang));
  j.field("slippage", b64_f32(slip));

  // Machine states: t, A, X, Y, B, F, eye xyz, fibre xyz, free length, kept point index.
  std::vector<float> st;
  std::vector<int> kept_states;
  const int ns = static_cast<int>(motion.states.size());
  for (int i = 0; i < ns; ++i) {
    const bool last_of_circuit =
        i + 1 == ns || motion.states[i + 1].ordinal != motion.states[i].ordinal;
    if (i % ks != 0 && !last_of_circuit) continue;
    const MachineState& s = motion.states[i];
    const Vec3 e = local(s.eye), p = local(s.position);
    int gi = 0;
    if (s.ordinal >= 0 && s.ordinal < static_cast<int>(kept_index.size()) && s.index >= 0 &&
        s.index < static_cast<int>(kept_index[s.ordinal].size()))
      gi = kept_index[s.ordinal][s.index];
    st.insert(st.end(), {float(s.t_s), float(s.a_deg), float(s.x_mm), float(s.y_mm), float(s.b_deg),
                         float(s.feed), float(e.x()), float(e.y()), float(e.z()), float(p.x()),
                         float(p.y()), float(p.z()), float(s.free_length), float(gi)});
    kept_states.push_back(i);
    ++out.states;
  }
  if (joints) out.joints_json = joints_data(motion, *joints, kept_states);
  j.field("state_stride", 14);
  j.field("states", b64_f32(st));

  j.key("cutlines").begin_array();
  for (const CutLine& l : plan.cutlines) {
    std::vector<float> cp;
    for (const Vec3& p : l.points) {
      const Vec3 x = local(p);
      cp.insert(cp.end(), {float(x.x()), float(x.y()), float(x.z())});
    }
    j.begin_object()
        .field("name", l.name)
        .field("closed", l.closed)
        .field("points", b64_f32(cp))
        .end_object();
  }
  j.end_array();

  j.field("mesh_positions", b64_f32(mesh.xyz));
  j.field("mesh_triangles", b64_u32(mesh.tris));
  out.triangles = static_cast<int>(mesh.tris.size() / 3);
  j.end_object();
  out.json = j.str();
  return out;
}

std::string escape_html(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else if (c == '&')
      o += "&amp;";
    else
      o += c;
  }
  return o;
}

// JSON inside <script>: "</" would close the element early.
std::string script_safe(const std::string& json) {
  std::string o;
  o.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    o += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') o += "\\";
  }
  return o;
}

const char* const kStyle = R"CSS(
html, body { margin: 0; height: 100%; overflow: hidden; background: #e9edf2;
  font: 13px/1.35 sans-serif; color: #1d2733; }
#view { position: absolute; left: 0; top: 0; right: 340px; bottom: 0; }
#panel { position: absolute; top: 0; right: 0; width: 340px; bottom: 0; overflow-y: auto;
  background: #fbfcfd; border-left: 1px solid #c9d1da; box-sizing: border-box; padding: 8px 10px; }
#panel h1 { font-size: 16px; margin: 2px 0 6px; }
#panel h2 { font-size: 13px; margin: 10px 0 4px; color: #3c4b5c; }
#panel table { border-collapse: collapse; width: 100%; }
#panel td { padding: 1px 3px; vertical-align: top; }
#panel td:first-child { color: #55606c; white-space: nowrap; }
.warn { color: #8a3b00; font-size: 12px; margin: 2px 0; }
.note { background: #fff3c4; border: 1px solid #e0c35a; padding: 4px; font-size: 12px; }
#legend canvas { width: 100%; height: 14px; display: block; }
#legend .sw { display: inline-block; width: 12px; height: 12px; margin: 1px; vertical-align: middle; }
#axes { font-family: monospace; font-size: 12px; }
#slider { width: 100%; }
label { margin-right: 8px; }
#hint { position: absolute; left: 8px; bottom: 6px; color: #5a6673; font-size: 11px; }
)CSS";

std::string page_html(const WindingPlan& plan, const std::string& json,
                      const std::string& joints_json) {
  std::string h;
  h.reserve(json.size() + 1000000);
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>";
  h += escape_html("windplan viewer: " + plan.job_name);
  h += "</title>\n<style>";
  h += kStyle;
  h += "</style>\n</head>\n<body>\n<div id=\"view\"></div>\n<div id=\"panel\"></div>\n"
       "<div id=\"hint\">drag: turn · right-drag or shift-drag: pan · wheel: zoom · "
       "double-click: reset view</div>\n";
  h += "<script id=\"windplan-data\" type=\"application/json\">";
  h += script_safe(json);
  if (!joints_json.empty()) {
    h += "</script>\n<script id=\"windplan-joints\" type=\"application/json\">";
    h += script_safe(joints_json);
  }
  h += "</script>\n<script>\n// three.js r111 (MIT licence), Debian package libjs-three\n";
  h += embedded::three_js();
  h += "\n</script>\n<script>\n";
  h += embedded::viewer_app_js();
  if (!joints_json.empty()) {
    h += "\n</script>\n<script>\n";
    h += embedded::viewer_joints_js();
  }
  h += "\n</script>\n</body>\n</html>\n";
  return h;
}

}  // namespace

ViewerPage viewer_page(const WindingPlan& plan, const Mesh& mandrel, const Motion& motion,
                       const ViewerOptions& opts, const ViewerJoints* joints) {
  std::string why;
  if (!opts.is_valid(&why)) throw InputError("viewer options: " + why);
  if (joints) {
    bool ok = joints->time.size() == motion.states.size() && !joints->series.empty();
    for (const JointSeries& js : joints->series) ok = ok && js.values.size() == joints->time.size();
    if (!ok)
      throw InputError("viewer: the robot's joints need one value per machine state (" +
                       std::to_string(motion.states.size()) + ")");
  }
  const AxisFrame frame = make_axis_frame(plan.axis);
  ViewerPage page;
  for (const Circuit& c : plan.circuits) page.points += static_cast<int>(c.points.size());
  page.states = static_cast<int>(motion.states.size());
  page.triangles = mandrel.num_faces();

  // Decimate until the page fits: the mandrel first when it alone takes over 40% of the budget
  // (vertex clustering, the cell growing by 1.5), then the points and states by a growing stride.
  const std::size_t fixed = std::strlen(embedded::three_js()) +
                            std::strlen(embedded::viewer_app_js()) + 20000 +
                            (joints ? std::strlen(embedded::viewer_joints_js()) + 1000 : 0);
  // Bytes per machine state on the page: 14 float32; a robot's joints add the series, the
  // robot's time, the planned time and the row (base64: 4/3).
  const double state_bytes = 56.0 + (joints ? 4.0 * (joints->series.size() + 3) : 0.0);
  const double budget = static_cast<double>(opts.max_bytes) - static_cast<double>(fixed);
  auto b64_size = [](double bytes) { return bytes * 4.0 / 3.0; };
  PageMesh mesh = cluster_mesh(mandrel, frame, 0.0);
  double cell = 0.0;
  if (b64_size(12.0 * (mesh.xyz.size() / 3 + mesh.tris.size() / 3)) > 0.4 * budget) {
    double lo = 1e300, hi = -1e300;
    for (const Vec3& p : mandrel.points()) {
      lo = std::min(lo, p.minCoeff());
      hi = std::max(hi, p.maxCoeff());
    }
    cell = std::max(1e-6, (hi - lo) / 400.0);
    while (b64_size(12.0 * (mesh.xyz.size() / 3 + mesh.tris.size() / 3)) > 0.4 * budget) {
      mesh = cluster_mesh(mandrel, frame, cell);
      cell *= 1.5;
    }
  }
  int k = 1, ks = 1;
  PageData data;
  std::string note;
  for (int attempt = 0; attempt < 60; ++attempt) {
    note.clear();
    if (k > 1 || ks > 1 || cell > 0.0) {
      note = "Decimated to stay under " + fmt("%.1f MB", opts.max_bytes / 1e6) + ": ";
      if (k > 1) note += "1 in " + std::to_string(k) + " fibre points, ";
      if (ks > 1) note += "1 in " + std::to_string(ks) + " machine points, ";
      if (cell > 0.0)
        note += "mandrel " + std::to_string(page.triangles) + " -> " +
                std::to_string(mesh.tris.size() / 3) + " triangles, ";
      note += "kept for the page only; the CSV and G-code files hold every point.";
    }
    data = page_data(plan, motion, frame, mesh, k, ks, note, joints);
    const double bytes = static_cast<double>(data.json.size() + data.joints_json.size());
    if (bytes <= budget) break;
    // Thin what takes room: the points (32 bytes each) and the states (56, more with a robot's
    // joints) whichever is over a quarter of the budget (base64: 4/3).
    const double over = bytes / budget;
    const int k0 = k, ks0 = ks;
    if (b64_size(32.0 * data.points) > 0.25 * budget)
      k = std::max(k + 1, static_cast<int>(std::ceil(k * over)));
    if (b64_size(state_bytes * data.states) > 0.25 * budget)
      ks = std::max(ks + 1, static_cast<int>(std::ceil(ks * over)));
    if (k == k0 && ks == ks0) {  // neither dominates: thin both
      k += 1;
      ks += 1;
    }
  }
  page.note = note;
  page.points_kept = data.points;
  page.states_kept = data.states;
  page.triangles_kept = data.triangles;
  page.html = page_html(plan, data.json, data.joints_json);
  return page;
}

}  // namespace windplan
