#include "export/plots/axes_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "export/plots/svg_util.h"

namespace windplan {

std::string axes_svg(const Motion& motion, const std::string& job_name,
                     const AxesSvgOptions& opts) {
  const double ml = 90, mr = 20, mt = 40, gap = 22, mb = 50;
  const int n_panels = 5;
  const double ph = opts.panel_height;
  const int height = static_cast<int>(mt + n_panels * ph + (n_panels - 1) * gap + mb);
  const double pw = opts.width - ml - mr;
  const auto& st = motion.states;
  const double t_end = st.empty() ? 1.0 : std::max(st.back().t_s, 1e-9);
  auto px = [&](double t) { return ml + t / t_end * pw; };

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << opts.width << "\" height=\""
    << height << "\" viewBox=\"0 0 " << opts.width << " " << height << "\">\n"
    << "<title>" << xml_escape("windplan machine axes: " + job_name) << "</title>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << opts.width << "\" height=\"" << height
    << "\" fill=\"white\"/>\n"
    << "<text x=\"" << ml << "\" y=\"22\" font-family=\"sans-serif\" font-size=\"15\">"
    << xml_escape(job_name) << ": machine axes against time (" << st.size()
    << " machine points, wind time " << f2(motion.wind_time) << " s)</text>\n";

  struct Axis {
    const char* name;
    std::string unit;
    double MachineState::*field;
    const char* colour;
  };
  const Axis axes[n_panels] = {
      {"A", "deg", &MachineState::a_deg, "#1f77b4"},
      {"X", "mm", &MachineState::x_mm, "#d62728"},
      {"Y", "mm", &MachineState::y_mm, "#2ca02c"},
      {"B", "deg", &MachineState::b_deg, "#9467bd"},
      {"F", motion.inverse_time ? "1/min" : "units/min", &MachineState::feed, "#8c564b"}};
  const int cols = std::max(1, static_cast<int>(pw));
  for (int a = 0; a < n_panels; ++a) {
    const Axis& ax = axes[a];
    const double top = mt + a * (ph + gap);
    double lo = 0.0, hi = 0.0;
    if (!st.empty()) {
      lo = hi = st.front().*ax.field;
      for (const MachineState& s : st) {
        lo = std::min(lo, s.*ax.field);
        hi = std::max(hi, s.*ax.field);
      }
    }
    if (!(hi - lo > 1e-9 * std::max(1.0, std::fabs(hi)))) {
      lo -= 1.0;
      hi += 1.0;
    }
    auto py = [&](double v) { return top + ph - (v - lo) / (hi - lo) * ph; };
    o << "<g class=\"panel\" data-axis=\"" << ax.name << "\" font-family=\"sans-serif\" "
      << "font-size=\"10\" fill=\"#333\">\n"
      << "<rect x=\"" << f2(ml) << "\" y=\"" << f2(top) << "\" width=\"" << f2(pw) << "\" height=\""
      << f2(ph) << "\" fill=\"none\" stroke=\"#333\" stroke-width=\"0.8\"/>\n"
      << "<text x=\"12\" y=\"" << f2(top + ph / 2 + 4) << "\" font-size=\"13\">" << ax.name << " ["
      << xml_escape(ax.unit) << "]</text>\n";
    o << value_grid(lo, hi, ml, pw, py);
    // Circuit boundaries.
    for (std::size_t i = 1; i < st.size(); ++i) {
      if (st[i].ordinal == st[i - 1].ordinal) continue;
      o << "<line x1=\"" << f2(px(st[i].t_s)) << "\" y1=\"" << f2(top) << "\" x2=\""
        << f2(px(st[i].t_s)) << "\" y2=\"" << f2(top + ph)
        << "\" stroke=\"#ddd\" stroke-width=\"0.5\"/>\n";
    }
    // Envelope per pixel column: entry, min, max, exit of the samples in the column, in order.
    o << "<polyline fill=\"none\" stroke=\"" << ax.colour << "\" stroke-width=\"1\" points=\""
      << envelope_points(
             st.size(), [&](std::size_t k) { return st[k].t_s; },
             [&](std::size_t k) { return st[k].*ax.field; }, px, py, ml, cols);
    o << "\"/>\n</g>\n";
  }
  // Time axis under the last panel.
  const double bottom = mt + n_panels * ph + (n_panels - 1) * gap;
  o << bottom_axis(t_end, bottom, ml, pw, px, "time t [s] (faint lines: circuit starts)")
    << "</svg>\n";
  return o.str();
}

}  // namespace windplan
