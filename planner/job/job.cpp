#include "planner/job/job.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/base/name_text.h"
#include "planner/job/config_node.h"
#include "planner/job/job_limits.h"
#include "planner/job/robot_config.h"

namespace windplan {

bool is_valid_job_name(const std::string& name, std::string* why) {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (name.empty()) return fail("must not be empty");
  if (name.size() > 128) return fail("is longer than 128 characters");
  if (name == "." || name == "..") return fail("'" + name + "' is not a name");
  if (name.find("..") != std::string::npos) return fail("must not contain '..'");
  for (const char c : name) {
    if (c == '/' || c == '\\') {
      return fail("must not contain '/' or '\\' (it becomes a folder name: out/<name>)");
    }
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return fail("must not contain control characters");
    }
  }
  if (name[0] == '.') return fail("must not start with '.'");
  std::string text_why;  // UTF-8, no format characters, not blank (geometry/base/name_text.h)
  if (!check_name_text(name, &text_why)) return fail(text_why);
  return true;
}

double to_millimetres(LengthUnit u) {
  switch (u) {
    case LengthUnit::Millimetre:
      return 1.0;
    case LengthUnit::Metre:
      return 1000.0;
    case LengthUnit::Inch:
      return 25.4;
  }
  return 1.0;
}

LengthUnit parse_length_unit(const std::string& s) {
  if (s == "mm") return LengthUnit::Millimetre;
  if (s == "m") return LengthUnit::Metre;
  if (s == "in") return LengthUnit::Inch;
  throw InputError("unknown length unit '" + s + "' (use mm, m or in)");
}

bool MandrelOptions::is_valid(std::string* why) const {
  if ((source == "mesh" || source == "cad") && file.empty()) {
    if (why) *why = "source: " + source + " needs a 'file:'";
    return false;
  }
  if (!tessellation.is_valid(why)) return false;
  if (!(remesh >= 0.0) || !std::isfinite(remesh)) {
    if (why) *why = "remesh must be >= 0 mm (0 = off)";
    return false;
  }
  if (has_axis && !(axis.direction.norm() > 1e-12)) {
    if (why) *why = "axis.direction must be a non-zero vector";
    return false;
  }
  if (!region.is_valid(why)) return false;
  if (!features.is_valid(why)) return false;
  if (!features.empty() && (source == "mesh" || source == "cad" || source == "bent_tube")) {
    if (why) *why = "features (bore, shafts, flanges, tabs) are for pipe, cone, vessel and section";
    return false;
  }
  if (source == "pipe") return pipe.is_valid(why);
  if (source == "cone") return cone.is_valid(why);
  if (source == "vessel") return vessel.is_valid(why);
  if (source == "bent_tube") return bent_tube.is_valid(why);
  if (source == "section") return section.is_valid(why);
  return true;
}

namespace {

// One dome: `type`, `aspect`, `polar_opening`, each optional (keeps *d's values when absent).
void decode_dome(ConfigNode n, DomeParams* d) {
  if (!n.present()) return;
  std::string type;
  if (n.get_choice("type", {"hemispherical", "elliptical", "isotensoid"}, &type)) {
    d->type = parse_dome_type(type);
  }
  n.get("aspect", &d->aspect);
  n.get("polar_opening", &d->polar_opening);
  n.finish();
}

// One section end: `type` (flat | dome), `height`, `opening`; keeps *e's values when absent.
void decode_section_end(ConfigNode n, SectionEndParams* e) {
  if (!n.present()) return;
  std::string type;
  if (n.get_choice("type", {"flat", "dome"}, &type)) e->dome = type == "dome";
  n.get("height", &e->height);
  n.get("opening", &e->opening);
  n.finish();
}

void decode_features(ConfigNode n, MandrelFeatures* f) {
  if (!n.present()) return;
  n.get("bore", &f->bore);
  for (const auto& [key, shaft] :
       {std::pair{"shaft_start", &f->shaft_start}, std::pair{"shaft_end", &f->shaft_end}}) {
    if (ConfigNode s = n.section(key); s.present()) {
      s.require("radius", &shaft->radius);
      s.require("length", &shaft->length);
      s.finish();
    }
  }
  for (ConfigNode fn : n.list("flanges")) {
    FlangeParams fl;
    fn.require("at", &fl.at);
    fn.require("radius", &fl.radius);
    fn.require("thickness", &fl.thickness);
    fn.get("bolts", &fl.bolts);
    fn.get("bolt_radius", &fl.bolt_radius);
    fn.get("pitch_radius", &fl.pitch_radius);
    fn.finish();
    f->flanges.push_back(fl);
  }
  for (ConfigNode tn : n.list("tabs")) {
    TabParams t;
    tn.require("at", &t.at);
    tn.get("count", &t.count);
    tn.get("angle", &t.angle);
    tn.get("reach", &t.reach);
    tn.get("width", &t.width);
    tn.get("thickness", &t.thickness);
    tn.get("hole_radius", &t.hole_radius);
    tn.finish();
    f->tabs.push_back(t);
  }
  n.finish();
  if (std::string why; !f->is_valid(&why, "features")) n.fail_here(why);
}

void decode_mandrel(ConfigNode n, const std::filesystem::path& base, MandrelOptions* m) {
  if (!n.present()) n.fail_here("the job needs a 'mandrel:' section");
  n.get_choice("source", {"mesh", "cad", "pipe", "cone", "vessel", "bent_tube", "section"},
               &m->source);
  std::string file;
  if (m->source == "mesh" || m->source == "cad") n.require("file", &file);
  if (!file.empty()) {
    m->file = (base / file).lexically_normal();
    std::error_code ec;
    if (std::filesystem::is_directory(m->file, ec)) {
      n.fail("file", "'" + m->file.string() + "' is a directory; give a mesh or CAD file");
    }
  }
  std::string units;
  if (n.get_choice("units", {"mm", "m", "in"}, &units)) m->units = parse_length_unit(units);
  n.get("repair", &m->repair);
  n.get("solid", &m->solid);
  n.get("linear_deflection", &m->tessellation.linear_deflection);
  m->angular_deflection_given = n.get("angular_deflection", &m->tessellation.angular_deflection);
  n.get("remesh", &m->remesh);
  if (ConfigNode a = n.section("axis"); a.present()) {
    std::array<double, 3> origin{0.0, 0.0, 0.0}, direction{0.0, 0.0, 1.0};
    a.get("origin", &origin);
    a.require("direction", &direction);
    a.finish();
    m->has_axis = true;
    m->axis.origin = Vec3(origin[0], origin[1], origin[2]);
    const Vec3 d(direction[0], direction[1], direction[2]);
    if (!(d.norm() > 1e-12)) a.fail("direction", "must be a non-zero vector");
    m->axis.direction = d.normalized();
  }
  if (ConfigNode r = n.section("region"); r.present()) {
    RegionOptions& g = m->region;
    g.enabled = true;
    if (ConfigNode c = r.section("centre_line"); c.present()) {
      // Ends on sections normal to the tube's centre line: from/to in mm of arc length, or
      // from_fraction/to_fraction of its length (one of each pair).
      g.centre_line = true;
      if (r.has("start") || r.has("end")) {
        r.fail("centre_line", "give either start/end (planes normal to the axis) or " +
                                  std::string("centre_line (sections normal to the centre line)"));
      }
      for (auto [key, value, fraction] : {std::tuple{"from", &g.from, &g.from_fraction},
                                          std::tuple{"to", &g.to, &g.to_fraction}}) {
        const std::string k = key, kf = k + "_fraction";
        if (c.has(k) && c.has(kf)) c.fail(kf, "give " + k + " (mm) or " + kf + ", not both");
        if (!c.has(k) && !c.has(kf)) c.fail(k, "missing: give " + k + " (mm) or " + kf);
        *fraction = c.has(kf);
        c.require(*fraction ? kf : k, value);
      }
      c.finish();
    } else {
      r.require("start", &g.start);
      r.require("end", &g.end);
    }
    r.get_choice("surface", {"outer", "inner"}, &g.surface);
    r.get("component", &g.component);
    r.get("min_fraction", &g.cut.min_fraction);
    r.finish();
    if (std::string why; !g.is_valid(&why)) r.fail_here(why);
  }
  decode_features(n.section("features"), &m->features);
  // The section of the chosen parametric shape; the others are rejected as unknown keys.
  if (m->source == "pipe") {
    ConfigNode p = n.section("pipe");
    if (!p.present()) n.fail("pipe", "source: pipe needs a 'pipe:' section (radius, length)");
    p.require("radius", &m->pipe.radius);
    p.require("length", &m->pipe.length);
    p.finish();
    p.check(m->pipe);
  } else if (m->source == "cone") {
    ConfigNode p = n.section("cone");
    if (!p.present()) {
      n.fail("cone", "source: cone needs a 'cone:' section (radius_start, radius_end, length)");
    }
    p.require("radius_start", &m->cone.radius_start);
    p.require("radius_end", &m->cone.radius_end);
    p.require("length", &m->cone.length);
    p.finish();
    p.check(m->cone);
  } else if (m->source == "vessel") {
    ConfigNode p = n.section("vessel");
    if (!p.present()) {
      n.fail("vessel", "source: vessel needs a 'vessel:' section (radius, length, dome)");
    }
    VesselParams& v = m->vessel;
    p.require("radius", &v.radius);
    p.require("length", &v.length);
    // `dome:` sets both domes; `dome_start:` / `dome_end:` override it per key.
    DomeParams both = v.dome_end;
    decode_dome(p.section("dome"), &both);
    v.dome_start = v.dome_end = both;
    const bool start_own = p.has("dome_start"), end_own = p.has("dome_end");
    decode_dome(p.section("dome_start"), &v.dome_start);
    decode_dome(p.section("dome_end"), &v.dome_end);
    p.finish();
    if (std::string why; !v.is_valid(&why)) {
      // Name the key the user wrote: `dome.x` when the faulty dome came from `dome:` alone.
      for (const auto& [key, own] : {std::pair{std::string("dome_start."), start_own},
                                     std::pair{std::string("dome_end."), end_own}}) {
        if (!own && why.rfind(key, 0) == 0) why = "dome." + why.substr(key.size());
      }
      p.fail_here(why);
    }
  } else if (m->source == "section") {
    ConfigNode p = n.section("section");
    if (!p.present()) {
      n.fail("section", "source: section needs a 'section:' section (shape, dimensions, length)");
    }
    SectionParams& sp = m->section;
    std::string shape = "ellipse";
    p.get_choice("shape", {"ellipse", "rounded_rectangle"}, &shape);
    sp.shape = shape == "ellipse" ? SectionShape::Ellipse : SectionShape::RoundedRectangle;
    if (sp.shape == SectionShape::Ellipse) {
      std::array<double, 2> ab{sp.semi_x, sp.semi_y};
      if (!p.get("semi_axes", &ab)) {
        p.fail_here("shape: ellipse needs 'semi_axes: [a, b]' (mm, along X and Y)");
      }
      sp.semi_x = ab[0];
      sp.semi_y = ab[1];
    } else {
      p.require("width", &sp.width);
      p.require("height", &sp.height);
      p.require("corner_radius", &sp.corner_radius);
    }
    p.require("length", &sp.length);
    SectionEndParams both;
    decode_section_end(p.section("ends"), &both);
    sp.end_start = sp.end_end = both;
    decode_section_end(p.section("end_start"), &sp.end_start);
    decode_section_end(p.section("end_end"), &sp.end_end);
    p.finish();
    p.check(sp);
  } else if (m->source == "bent_tube") {
    ConfigNode p = n.section("bent_tube");
    if (!p.present()) {
      n.fail("bent_tube",
             "source: bent_tube needs a 'bent_tube:' section (radius, segments, bends)");
    }
    BentTubeParams& b = m->bent_tube;
    p.require("radius", &b.radius);
    p.require("segments", &b.segments);
    b.bends.clear();
    for (ConfigNode bn : p.list("bends")) {
      BendParams bend;
      bn.require("angle", &bend.angle);
      bn.require("radius", &bend.radius);
      bn.get("plane_angle", &bend.plane_angle);
      bn.finish();
      b.bends.push_back(bend);
    }
    p.finish();
    p.check(b);
  }
  n.finish();
  n.check(*m);
}

// ---- machine: and output: (export/ reads them) ----

/// Rejects keys of `n` outside `known` (for sections read partly by hand, like envelope.profile).
void reject_unknown_keys(const ConfigNode& n, const std::vector<std::string>& known) {
  if (!n.present()) return;
  for (auto it = n.yaml().begin(); it != n.yaml().end(); ++it) {
    const std::string k = it->first.as<std::string>();
    bool ok = false;
    for (const std::string& u : known) ok = ok || u == k;
    if (!ok) {
      std::string allowed;
      for (const std::string& u : known) allowed += (allowed.empty() ? "" : ", ") + u;
      throw ConfigError(n.file() + ":" + std::to_string(it->first.Mark().line + 1) +
                        ": unknown key '" + (n.path().empty() ? k : n.path() + "." + k) +
                        "' (known: " + allowed + ")");
    }
  }
}

void decode_envelope(ConfigNode n, EnvelopeOptions* e) {
  reject_unknown_keys(n, {"clearance", "profile", "free_length", "radius"});
  int modes = 0;
  modes += n.has("clearance");
  modes += n.has("profile");
  modes += n.has("free_length");
  if (modes > 1) n.fail_here("give only one of clearance, profile, free_length");
  n.get("clearance", &e->clearance);
  n.get("free_length", &e->free_length);
  n.get("radius", &e->radius);
  if (n.has("profile")) {
    const YAML::Node p = n.yaml()["profile"];
    if (!p.IsSequence()) n.fail("profile", "expected a list of [x, r] pairs (mm)");
    for (std::size_t i = 0; i < p.size(); ++i) {
      std::array<double, 2> xr{};
      bool ok = p[i].IsSequence() && p[i].size() == 2;
      for (std::size_t j = 0; ok && j < 2; ++j) {
        try {
          xr[j] = p[i][j].as<double>();
          ok = std::isfinite(xr[j]);
        } catch (const YAML::Exception&) {
          ok = false;
        }
      }
      if (!ok) n.fail("profile", "element " + std::to_string(i) + " must be [x, r] in mm");
      e->profile.push_back(xr);
    }
    if (e->profile.empty()) n.fail("profile", "the list is empty");
  }
  n.check(*e);
}

void decode_axis(ConfigNode n, AxisOptions* a) {
  n.get("letter", &a->letter);
  n.get("sign", &a->sign);
  n.get("offset", &a->offset);
  n.get("min", &a->min);
  n.get("max", &a->max);
  n.get("max_velocity", &a->max_velocity);
  n.get("max_acceleration", &a->max_acceleration);
  n.finish();
  n.check(*a);
}

void decode_machine(ConfigNode n, const std::filesystem::path& base, MachineOptions* m,
                    bool in_profile = false) {
  if (!n.present()) return;
  // A machine profile (its own YAML file of machine keys) first; the job's keys override it.
  std::string profile;
  if (!in_profile && n.get("profile", &profile)) {
    if (profile.empty()) n.fail("profile", "must name a machine profile file");
    const std::filesystem::path file = (base / profile).lexically_normal();
    if (!std::filesystem::exists(file)) {
      n.fail("profile", "the machine profile " + file.string() + " does not exist");
    }
    ConfigNode p = ConfigNode::load_file(file, "machine profile");
    if (!p.present() || !p.yaml().IsMap()) {
      throw ConfigError(file.string() + ": a machine profile must be a map of machine keys");
    }
    decode_machine(p, file.parent_path(), m, true);
    m->profile = file.string();
  }
  n.get_choice("kind", {"lathe2", "lathe4", "robot"}, &m->kind);
  n.get("chord_tolerance", &m->chord_tolerance);
  n.get("max_fibre_speed", &m->max_fibre_speed);
  n.get("tangent_window", &m->tangent_window);
  n.get("monotone_axes", &m->monotone_axes);
  n.get("replay_tolerance", &m->replay_tolerance);
  decode_envelope(n.section("envelope"), &m->envelope);
  ConfigNode axes = n.section("axes");
  decode_axis(axes.section("A"), &m->a);
  decode_axis(axes.section("X"), &m->x);
  decode_axis(axes.section("Y"), &m->y);
  decode_axis(axes.section("B"), &m->b);
  axes.finish();
  ConfigNode g = n.section("gcode");
  g.get_choice("dialect", {"linuxcnc", "marlin", "fanuc"}, &m->gcode.dialect);
  g.get_choice("feed", {"auto", "inverse_time", "per_minute"}, &m->gcode.feed);
  g.get("program_number", &m->gcode.program_number);
  g.finish();
  g.check(m->gcode);
  decode_robot(n.section("robot"), base, &m->robot);  // planner/job/robot_config.h
  n.finish();
  n.check(*m);
}

void decode_output(ConfigNode n, const std::filesystem::path& base, OutputOptions* o) {
  if (!n.present()) return;
  std::string dir;
  if (n.get("directory", &dir)) {
    if (dir.empty()) n.fail("directory", "must not be empty");
    o->directory = (base / dir).lexically_normal();
  }
  n.get("csv", &o->csv);
  n.get("gcode", &o->gcode);
  n.get("report", &o->report);
  n.get("ply", &o->ply);
  n.get("svg", &o->svg);
  n.get("viewer", &o->viewer);
  n.get("timings", &o->timings);
  n.finish();
  n.check(*o);
}

// ---- cutlines: (planner/cutlines/cutlines.h) ----

void decode_cutlines(ConfigNode& root, const std::filesystem::path& base,
                     std::vector<CutLineOptions>* cuts) {
  int i = 0;
  for (ConfigNode n : root.list("cutlines")) {
    CutLineOptions c;
    c.name = "cut" + std::to_string(++i);
    n.get("name", &c.name);
    if (ConfigNode p = n.section("plane"); p.present()) {
      std::array<double, 3> nrm{0.0, 0.0, 1.0};
      p.require("normal", &nrm);
      p.require("offset", &c.offset);
      p.finish();
      c.has_plane = true;
      c.normal = Vec3(nrm[0], nrm[1], nrm[2]);
      if (!(c.normal.norm() > 1e-12) || !std::isfinite(c.normal.norm())) {
        p.fail("normal", "must be a non-zero vector");
      }
    }
    c.has_station = n.get("station", &c.station);
    std::string init;
    if (n.get("init", &init)) {
      if (init.empty()) n.fail("init", "must name a CSV file");
      c.init = (base / init).lexically_normal();
    }
    n.get("closed", &c.closed);
    std::array<double, 3> from{0.0, 0.0, 0.0}, to{0.0, 0.0, 0.0};
    if (!c.closed) {
      n.require("from", &from);
      n.require("to", &to);
    } else {
      for (const char* k : {"from", "to"}) {
        if (n.has(k)) n.fail(k, "is only for open cut-lines (closed: false)");
      }
    }
    c.from = Vec3(from[0], from[1], from[2]);
    c.to = Vec3(to[0], to[1], to[2]);
    n.get_choice("normal_mode", {"free", "fixed", "cone"}, &c.normal_mode);
    n.get("max_tilt_deg", &c.max_tilt_deg);
    n.get("keep_offset", &c.keep_offset);
    n.finish();
    n.check(c);
    cuts->push_back(std::move(c));
  }
}

// ---- girth: (planner/girth/girth.h) ----

void decode_girth(ConfigNode n, GirthOptions* g) {
  if (!n.present()) return;
  n.get("samples", &g->samples);
  n.get_choice("placement", {"rings", "farthest"}, &g->placement);
  n.get("rings", &g->rings);
  n.finish();
  n.check(*g);
}

// ---- winding: (planner/winding/winding_options.h) ----

void decode_winding(ConfigNode n, WindingOptions* w) {
  if (!n.present()) return;
  w->turns_given = n.get("turns", &w->turns);
  if (w->turns_given && (n.has("angle") || n.has("turnaround"))) {
    // Each fixes the turnaround radius c; beside angle or turnaround, turns was ignored without a
    // word (a pipe and a mesh tube wound byte-identically with and without it).
    n.fail("turns", std::string("give one of turns, angle or turnaround: each fixes the turnaround "
                                "radius c, and ") +
                        (n.has("angle") ? "angle" : "turnaround") + " would leave turns unused");
  }
  std::string circuits;
  if (n.has("pattern")) {
    std::string word;
    if (n.is_map("pattern")) {
      ConfigNode pat = n.section("pattern");
      pat.require("circuits", &w->circuits);
      pat.get("skip", &w->skip);
      pat.finish();
      if (w->circuits < 1) pat.fail("circuits", "must be >= 1");
      if (w->skip < 1 && w->circuits > 1) pat.fail("skip", "must be >= 1");
    } else if (n.get("pattern", &word) && word != "auto") {
      n.fail("pattern", "must be auto or {circuits: K, skip: p} (got '" + word + "')");
    }
    if (n.has("circuits")) n.fail("circuits", "give winding.pattern or winding.circuits, not both");
  }
  if (n.get("circuits", &circuits)) {
    if (circuits == "auto") {
      w->circuits = 0;
    } else {
      std::size_t used = 0;
      int k = 0;
      try {
        k = std::stoi(circuits, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != circuits.size() || k < 1) {
        n.fail("circuits", "must be an integer >= 1 or auto (got '" + circuits + "')");
      }
      w->circuits = k;
    }
  }
  n.get("band_width", &w->band_width);
  n.get("beta", &w->beta);
  n.get("mu", &w->mu);
  n.get("slippage", &w->slippage);
  n.get("start_station", &w->start_station);
  n.get("end_station", &w->end_station);
  n.get("curvature_window", &w->curvature_window);
  n.get("meridians", &w->meridians);
  n.get("turnaround", &w->turnaround);
  n.get("angle", &w->angle);
  n.get("turnaround_window", &w->turnaround_window);
  n.get("coverage_stations", &w->coverage_stations);
  if (n.has("pins")) {  // pins at the ends of a friction layer on a bent tube
    if (!n.is_map("pins")) n.fail("pins", "must be {count: N, diameter: mm, offset: mm}");
    ConfigNode pins = n.section("pins");
    pins.require("count", &w->pin_count);
    pins.get("diameter", &w->pin_diameter);
    pins.get("offset", &w->pin_offset);
    pins.finish();
  }
  n.finish();
  n.check(*w);
}

// ---- layers: (planner/layup/layers.h) and material: (planner/layup/material.h) ----

void decode_layers(ConfigNode& root, const WindingOptions& winding,
                   std::vector<LayerOptions>* layers) {
  if (!root.has("layers")) return;
  std::vector<ConfigNode> list = root.list("layers");
  if (list.empty()) {
    root.fail("layers",
              "the list is empty: give at least one layer (kind: helical or hoop), or leave "
              "'layers:' out for one helical layer made of 'winding:'");
  }
  std::vector<int> count(2, 0);
  for (ConfigNode& n : list) {
    LayerOptions L;
    std::string kind;
    if (!n.get_choice("kind", {"helical", "hoop"}, &kind)) {
      n.fail_here("a layer needs 'kind: helical' or 'kind: hoop'");
    }
    L.kind = kind == "hoop" ? LayerKind::Hoop : LayerKind::Helical;
    L.name = kind + std::to_string(++count[L.kind == LayerKind::Hoop]);
    n.get("name", &L.name);
    if (L.kind == LayerKind::Helical) {
      L.winding = winding;
      decode_winding(n, &L.winding);  // the layer's own winding keys; finish() and check()
    } else {
      L.hoop.band_width = winding.band_width;
      L.hoop.mu = winding.mu;
      n.get("band_width", &L.hoop.band_width);
      n.get("mu", &L.hoop.mu);
      n.get("overlap", &L.hoop.overlap);
      n.get("passes", &L.hoop.passes);
      n.get("reversal_friction", &L.hoop.reversal_friction);
      n.get("point_spacing", &L.hoop.point_spacing);
      n.get("meridians", &L.hoop.meridians);
      std::array<double, 2> range{};
      if (n.get("range", &range)) {
        L.hoop.x0 = range[0];
        L.hoop.x1 = range[1];
      }
      n.finish();
      n.check(L.hoop);
    }
    layers->push_back(L);
  }
}

void decode_material(ConfigNode n, MaterialOptions* m) {
  if (!n.present()) return;
  if (n.has("tex") && n.has("linear_density")) {
    n.fail("linear_density", "give either tex (g/km) or linear_density (g/m), not both");
  }
  if (n.has("tows") && n.has("band_thickness")) {
    n.fail("band_thickness", "give either tows (per band) or band_thickness (mm), not both");
  }
  n.get("tex", &m->tex);
  double g_per_m = 0.0;
  if (n.get("linear_density", &g_per_m)) {
    if (!(g_per_m > 0.0)) n.fail("linear_density", "must be > 0 g/m");
    m->tex = 1000.0 * g_per_m;
  }
  n.get("fibre_density", &m->fibre_density);
  n.get("resin_density", &m->resin_density);
  n.get("fibre_volume_fraction", &m->fibre_volume_fraction);
  n.get("tows", &m->tows);
  n.get("band_thickness", &m->band_thickness);
  n.finish();
  n.check(*m);
}

// ---- design: (planner/layup/design.h) ----

void decode_design(ConfigNode& root, Job* job) {
  ConfigNode n = root.section("design");
  if (!n.present()) return;
  DesignOptions& d = job->design;
  d.present = true;
  const std::string& src = job->mandrel.source;
  if (src != "vessel" && src != "pipe") {
    root.fail("design",
              "sizing and the structural model need a mandrel of source vessel or pipe "
              "(this one is '" +
                  src + "')");
  }
  n.get("pressure", &d.pressure);
  n.get("burst_factor", &d.burst_factor);
  n.get("fibre_strength", &d.fibre_strength);
  n.get("fibre_modulus", &d.ply.fibre_modulus);
  n.get("fibre_transverse_modulus", &d.ply.fibre_transverse_modulus);
  n.get("fibre_shear_modulus", &d.ply.fibre_shear_modulus);
  n.get("fibre_poisson", &d.ply.fibre_poisson);
  n.get("resin_modulus", &d.ply.resin_modulus);
  n.get("resin_poisson", &d.ply.resin_poisson);
  d.ply.volume_fraction = job->material.fibre_volume_fraction;
  n.get("fibre_volume_fraction", &d.ply.volume_fraction);
  n.get("transverse_strength", &d.transverse_strength);
  n.get("shear_strength", &d.shear_strength);
  std::string model;
  if (n.get_choice("dome_thickness", {"continuity", "spline"}, &model)) {
    d.dome_thickness =
        model == "spline" ? DomeThicknessModel::Spline : DomeThicknessModel::Continuity;
  }
  n.get("turnaround_stagger", &d.turnaround_stagger);
  n.get("pot_life", &d.pot_life);
  n.get("fea_edge", &d.fea_edge);
  n.finish();
  std::string why;
  if (!d.is_valid(&why)) {
    const std::size_t colon = why.find(": ");
    n.fail(why.substr(0, colon), why.substr(colon + 2));
  }
  if (!d.has_pressure() || !job->layers.empty()) return;
  // Sizing: the cylinder radius and the helical angle on it.
  const WindingOptions& w = job->winding;
  double radius = 0.0, angle = std::nan("");
  if (src == "vessel") {
    radius = job->mandrel.vessel.radius;
    double c = w.turnaround;
    if (std::isnan(c) && std::isnan(w.angle)) {
      c = std::max(job->mandrel.vessel.dome_start.polar_opening,
                   job->mandrel.vessel.dome_end.polar_opening) +
          0.5 * w.band_width;
    }
    angle = std::isnan(w.angle) ? std::asin(std::min(1.0, c / radius)) * 180.0 / M_PI : w.angle;
  } else {
    radius = job->mandrel.pipe.radius;
    angle = w.angle;
    if (std::isnan(angle)) {
      n.fail("pressure", "sizing a pipe needs the helical angle: set winding.angle (deg)");
    }
  }
  if (!(angle > 0.0 && angle < 90.0)) {
    n.fail("pressure", "the helical angle on the cylinder (" + format_number("%g", angle) +
                           " deg) is outside (0, 90)");
  }
  job->sizing = design_layup(d, radius, angle, w, job->material.thickness(w.band_width));
  job->layers = job->sizing.layers;
  job->sized = true;
}

Job decode_job(ConfigNode root, const std::filesystem::path& file) {
  Job job;
  job.path = std::filesystem::absolute(file).lexically_normal();
  job.name = file.stem().string();
  if (root.get("name", &job.name)) {
    std::string why;
    if (!is_valid_job_name(job.name, &why)) root.fail("name", why);
  } else if (std::string why; !is_valid_job_name(job.name, &why)) {
    throw ConfigError(file.string() + ": the job name taken from the file name is not usable: " +
                      why + "; set 'name:'");
  }
  const std::filesystem::path base = job.path.parent_path();
  decode_mandrel(root.section("mandrel"), base, &job.mandrel);
  decode_machine(root.section("machine"), base, &job.machine);
  decode_output(root.section("output"), base, &job.output);
  decode_winding(root.section("winding"), &job.winding);
  // A bent tube's tessellation fitted to its bends and band (issue 25; geometry/cad/tessellate.h).
  if (job.mandrel.source == "bent_tube" && !job.mandrel.angular_deflection_given) {
    double rho = job.mandrel.bent_tube.radius;
    for (const BendParams& b : job.mandrel.bent_tube.bends) {
      rho = std::min(rho, b.radius - job.mandrel.bent_tube.radius);
    }
    job.mandrel.tessellation.angular_deflection =
        fitted_angular_deflection(rho, job.winding.band_width);
  }
  decode_girth(root.section("girth"), &job.girth);
  decode_cutlines(root, base, &job.cutlines);
  decode_layers(root, job.winding, &job.layers);
  decode_material(root.section("material"), &job.material);
  decode_design(root, &job);
  root.finish();
  check_job_limits(job, root);
  return job;
}

}  // namespace

Job load_job(const std::filesystem::path& file) {
  return decode_job(ConfigNode::load_file(file), file);
}

Job load_job_from_string(const std::string& yaml, const std::filesystem::path& file) {
  return decode_job(ConfigNode::load_string(yaml, file.string()), file);
}

}  // namespace windplan
