#include "export/files/layup_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/base/format_number.h"

namespace windplan {

namespace {

std::string fmt(const char* f, double v) {
  return std::isnan(v) ? std::string("-") : format_number(f, v);
}

struct Totals {
  double band = 0.0, fibre = 0.0, fibre_mass = 0.0, resin_mass = 0.0, time = 0.0;
  double thickness_cylinder = std::nan("");  // NaN: no layer has a cylinder figure
};

Totals totals(const WindingPlan& plan, const std::vector<double>& times) {
  Totals t;
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerSummary& L = plan.layers[l];
    t.band += L.band_length;
    t.fibre += L.fibre_length;
    t.fibre_mass += L.fibre_mass;
    t.resin_mass += L.resin_mass;
    t.time += times[l];
    if (!std::isnan(L.thickness_cylinder)) {
      t.thickness_cylinder =
          (std::isnan(t.thickness_cylinder) ? 0.0 : t.thickness_cylinder) + L.thickness_cylinder;
    }
  }
  return t;
}

}  // namespace

std::vector<double> layer_wind_times(const WindingPlan& plan, const Motion& motion) {
  std::vector<double> t(plan.layers.size(), 0.0);
  for (const MachineState& st : motion.states) {
    for (std::size_t l = 0; l < plan.layers.size(); ++l) {
      const LayerSummary& L = plan.layers[l];
      if (st.ordinal >= L.first_circuit && st.ordinal < L.first_circuit + L.circuit_count) {
        t[l] += st.duration;
        break;
      }
    }
  }
  return t;
}

void layers_json(JsonWriter& j, const WindingPlan& plan, const Motion& motion) {
  if (plan.layers.empty()) return;
  const std::vector<double> times = layer_wind_times(plan, motion);
  j.key("layers").begin_array();
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerSummary& L = plan.layers[l];
    j.begin_object()
        .field("name", L.name)
        .field("kind", L.kind)
        .field("first_circuit", L.first_circuit)
        .field("circuit_count", L.circuit_count)
        .field("circuits", L.circuits)
        .field("band_width_mm", L.band_width)
        .field("band_thickness_mm", L.band_thickness)
        .field("angle_deg", L.angle)
        .field("clairaut_mm", L.clairaut)
        .field("pitch_mm", L.pitch)
        .field("coverage", L.coverage)
        .field("surface_radius_mm", L.surface_radius)
        .field("thickness_cylinder_mm", L.thickness_cylinder)
        .field("thickness_turnaround_mm", L.thickness_turnaround)
        .field("thickness_max_mm", L.thickness_max)
        .field("max_slippage", L.max_slippage)
        .field("turnaround_slippage", L.turnaround_slippage)
        .field("band_length_mm", L.band_length)
        .field("fibre_length_mm", L.fibre_length)
        .field("fibre_mass_g", L.fibre_mass)
        .field("resin_mass_g", L.resin_mass)
        .field("wind_time_s", times[l])
        .end_object();
  }
  j.end_array();
  const Totals t = totals(plan, times);
  j.key("laminate")
      .begin_object()
      .field("layers", static_cast<int>(plan.layers.size()))
      .field("thickness_cylinder_mm", t.thickness_cylinder)
      .field("band_length_mm", t.band)
      .field("fibre_length_mm", t.fibre)
      .field("fibre_mass_g", t.fibre_mass)
      .field("resin_mass_g", t.resin_mass)
      .field("composite_mass_g", t.fibre_mass + t.resin_mass)
      .field("wind_time_s", t.time)
      .end_object();
}

std::string layers_markdown(const WindingPlan& plan, const Motion& motion) {
  if (plan.layers.empty()) return "";
  const std::vector<double> times = layer_wind_times(plan, motion);
  std::ostringstream o;
  o << "\n## Layers\n\n"
    << "| layer | kind | angle [deg] | thickness cylinder / turnaround / max [mm] | fibre [m] | "
       "fibre [g] | resin [g] | time [s] |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerSummary& L = plan.layers[l];
    o << "| " << l + 1 << " " << L.name << " | " << L.kind << " | " << fmt("%.3f", L.angle) << " | "
      << fmt("%.4f", L.thickness_cylinder) << " / " << fmt("%.4f", L.thickness_turnaround) << " / "
      << fmt("%.4f", L.thickness_max) << " | " << fmt("%.3f", 1e-3 * L.fibre_length) << " | "
      << fmt("%.2f", L.fibre_mass) << " | " << fmt("%.2f", L.resin_mass) << " | "
      << fmt("%.2f", times[l]) << " |\n";
  }
  const Totals t = totals(plan, times);
  o << "| total | | | " << fmt("%.4f", t.thickness_cylinder) << " (cylinder) | "
    << fmt("%.3f", 1e-3 * t.fibre) << " | " << fmt("%.2f", t.fibre_mass) << " | "
    << fmt("%.2f", t.resin_mass) << " | " << fmt("%.2f", t.time) << " |\n";
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerSummary& L = plan.layers[l];
    o << "\n### Layer " << l + 1 << ": " << L.name << " (" << L.kind << ")\n\n"
      << "| figure | value |\n|---|---|\n"
      << "| circuits in the plan | " << L.first_circuit << " to "
      << L.first_circuit + L.circuit_count - 1 << " |\n"
      << "| " << (L.kind == "hoop" ? "passes" : "circuits K") << " | " << L.circuits << " |\n"
      << "| wound on radius | " << fmt("%.3f", L.surface_radius) << " mm |\n"
      << "| band | " << fmt("%.3f", L.band_width) << " mm wide, " << fmt("%.4f", L.band_thickness)
      << " mm thick |\n"
      << "| angle (measured) | " << fmt("%.3f", L.angle) << " deg |\n";
    if (L.kind == "hoop") {
      o << "| pitch | " << fmt("%.3f", L.pitch) << " mm |\n"
        << "| coverage of the range (measured) | " << fmt("%.4f", L.coverage) << " |\n"
        << "| reversal max slippage | " << fmt("%.4f", L.turnaround_slippage) << " |\n";
    } else {
      o << "| Clairaut constant c (measured) | " << fmt("%.3f", L.clairaut) << " mm |\n"
        << "| cover factor | " << fmt("%.4f", L.coverage) << " |\n"
        << "| turnaround max slippage | " << fmt("%.4f", L.turnaround_slippage) << " |\n";
    }
    o << "| passes max slippage | " << fmt("%.4f", L.max_slippage) << " |\n"
      << "| thickness: cylinder / turnaround / max | " << fmt("%.4f", L.thickness_cylinder) << " / "
      << fmt("%.4f", L.thickness_turnaround) << " / " << fmt("%.4f", L.thickness_max) << " mm |\n"
      << "| band length | " << fmt("%.3f", L.band_length) << " mm |\n"
      << "| fibre (tow) length | " << fmt("%.3f", L.fibre_length) << " mm |\n"
      << "| fibre / resin mass | " << fmt("%.3f", L.fibre_mass) << " / "
      << fmt("%.3f", L.resin_mass) << " g |\n"
      << "| wind time | " << fmt("%.3f", times[l]) << " s |\n";
  }
  return o.str();
}

std::string layers_summary(const WindingPlan& plan, const Motion& motion) {
  if (plan.layers.empty()) return "";
  const std::vector<double> times = layer_wind_times(plan, motion);
  std::ostringstream o;
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerSummary& L = plan.layers[l];
    char buf[256];
    std::snprintf(
        buf, sizeof buf, "  layer %-2zu %-10s %-7s %6.2f deg  t %s mm  %s g fibre  %.1f s\n", l + 1,
        L.name.c_str(), L.kind.c_str(), L.angle, fmt("%.3f", L.thickness_cylinder).c_str(),
        fmt("%.1f", L.fibre_mass).c_str(), times[l]);
    o << buf;
  }
  const Totals t = totals(plan, times);
  o << "  laminate         " << fmt("%.3f", t.thickness_cylinder) << " mm on the cylinder, "
    << fmt("%.1f", t.fibre_mass) << " g fibre + " << fmt("%.1f", t.resin_mass) << " g resin\n";
  return o.str();
}

}  // namespace windplan
