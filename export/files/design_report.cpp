#include "export/files/design_report.h"

#include <cmath>
#include <sstream>

#include "geometry/base/format_number.h"

namespace windplan {

namespace {

std::string f(const char* fmt, double v) {
  return std::isfinite(v) ? format_number(fmt, v) : std::string("-");
}

}  // namespace

std::string pot_life_warning(const DesignOptions& d, double t) {
  if (!std::isfinite(d.pot_life) || !(t > 60.0 * d.pot_life)) return "";
  return "the part winds for " + format_number("%.1f", t / 60.0) +
         " min, beyond the resin's pot life of " + format_number("%g", d.pot_life) +
         " min (design.pot_life): split the winding or use a slower resin";
}

std::string design_markdown(const DesignOptions& d, bool sized, const DesignLayup& s,
                            const LayupResult& layup, const std::vector<double>& times,
                            bool model_written) {
  std::ostringstream o;
  const WindingPlan& plan = layup.plan;
  o << "# " << plan.job_name << ": design\n\n## Load and ply\n\n| figure | value |\n|---|---|\n";
  if (d.has_pressure()) {
    o << "| operating pressure | " << f("%g", d.pressure) << " MPa |\n"
      << "| burst factor | " << f("%g", d.burst_factor) << " (design burst pressure "
      << f("%.4g", d.design_pressure()) << " MPa) |\n"
      << "| allowable fibre-direction stress | fibre strength " << f("%g", d.fibre_strength)
      << " MPa x V_f " << f("%g", d.ply.volume_fraction) << " = " << f("%.5g", d.allowable_stress())
      << " MPa |\n";
  } else {
    o << "| operating pressure | not given: no sizing, no burst check |\n";
  }
  const ElasticConstants c = rule_of_mixtures(d.ply);
  o << "| ply (rule of mixtures) | E1 " << f("%.6g", c.e1) << ", E2 " << f("%.6g", c.e2) << ", G12 "
    << f("%.6g", c.g12) << " MPa, nu12 " << f("%.4g", c.nu12) << ", nu23 " << f("%.4g", c.nu23)
    << " |\n"
    << "| dome thickness model | " << to_string(d.dome_thickness) << " |\n"
    << "| turnaround stagger | " << f("%g", d.turnaround_stagger)
    << " band widths per helical layer |\n";
  if (sized) {
    o << "\n## Netting sizing\n\n| figure | value |\n|---|---|\n"
      << "| cylinder radius R | " << f("%.4g", s.radius) << " mm |\n"
      << "| helical angle on the cylinder | " << f("%.4f", s.angle_deg) << " deg |\n"
      << "| required helical thickness p R / (2 sigma cos^2 a) | "
      << f("%.4f", s.required.helical_thickness) << " mm |\n"
      << "| required hoop thickness p R (2 - tan^2 a) / (2 sigma) | "
      << f("%.4f", s.required.hoop_thickness) << " mm |\n"
      << "| one layer (two bands) | " << f("%.4f", s.layer_thickness) << " mm |\n"
      << "| layers | " << s.helical_layers << " helical, " << s.hoop_layers << " hoop |\n";
  }
  if (layup.has_netting) {
    const NettingBurst& b = layup.netting;
    o << "\n## Netting burst pressure of the wound laminate\n\n"
      << "On R = " << f("%.4g", layup.netting_radius)
      << " mm, each layer's measured angle and cylinder thickness; capacities in MPa of "
         "pressure.\n\n| layer | angle [deg] | thickness [mm] | axial capacity | hoop capacity | "
         "burst once laid |\n|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < plan.layers.size() && k < b.burst.size(); ++k) {
      const LayerSummary& L = plan.layers[k];
      o << "| " << k + 1 << " " << L.name << " | " << f("%.3f", L.angle) << " | "
        << f("%.4f", L.thickness_cylinder) << " | " << f("%.3f", b.axial_capacity[k]) << " | "
        << f("%.3f", b.hoop_capacity[k]) << " | " << f("%.3f", b.burst[k]) << " |\n";
    }
    o << "\nBurst pressure " << f("%.3f", b.pressure) << " MPa (" << b.governing
      << " governs; axial " << f("%.3f", b.axial) << ", hoop " << f("%.3f", b.hoop)
      << "): " << f("%.3f", b.pressure / d.pressure) << " x the operating pressure (burst factor "
      << f("%g", d.burst_factor) << (b.pressure >= d.design_pressure() ? ": met" : ": NOT met")
      << ").\n";
  }
  o << "\n## Time and cost per layer\n\n| layer | wind time [s] | fibre [g] | resin [g] |\n"
       "|---|---|---|---|\n";
  double tt = 0.0, fm = 0.0, rm = 0.0;
  for (std::size_t k = 0; k < plan.layers.size(); ++k) {
    const LayerSummary& L = plan.layers[k];
    const double t = k < times.size() ? times[k] : std::nan("");
    o << "| " << k + 1 << " " << L.name << " | " << f("%.2f", t) << " | " << f("%.2f", L.fibre_mass)
      << " | " << f("%.2f", L.resin_mass) << " |\n";
    tt += t;
    fm += L.fibre_mass;
    rm += L.resin_mass;
  }
  o << "| total | " << f("%.2f", tt) << " | " << f("%.2f", fm) << " | " << f("%.2f", rm)
    << " |\n\n";
  if (std::isfinite(d.pot_life)) {
    const std::string w = pot_life_warning(d, tt);
    o << "Pot life " << f("%g", d.pot_life) << " min, wind time " << f("%.1f", tt / 60.0)
      << " min: " << (w.empty() ? "fits" : "WARNING: " + w) << ".\n";
  }
  if (model_written) {
    o << "\n## Structural model\n\nmodel.inp: layered S6 shells (CalculiX/Abaqus input) under "
      << f("%g", d.has_pressure() ? d.pressure : 1.0)
      << " MPa, plies listed in model_plies.csv. Solve and check the first-ply failure "
         "(max-strain) with `windplan check-fea <job.yaml>`.\n";
  }
  return o.str();
}

}  // namespace windplan
