#include "export/plots/stability_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "export/plots/svg_util.h"

namespace windplan {

std::string stability_svg(const WindingPlan& plan, const StabilitySvgOptions& opts) {
  const PlanMetrics& m = plan.metrics;
  const double mu = m.friction;
  // The circuit with the largest measured |k_g/k_n| (the first of equals).
  int worst = -1;
  double top_slip = 0.0;
  for (std::size_t k = 0; k < plan.circuits.size(); ++k) {
    for (const FibrePoint& q : plan.circuits[k].points) {
      if (worst < 0 || q.slippage > top_slip) {
        top_slip = std::max(top_slip, q.slippage);
        worst = static_cast<int>(k);
      }
    }
  }
  const double ml = 90, mr = 20, mt = 56, gap = 30, mb = 50;
  const double ph = opts.panel_height, pw = opts.width - ml - mr;
  const int height = static_cast<int>(mt + 2 * ph + gap + mb);
  const int cols = std::max(1, static_cast<int>(pw));
  static const std::vector<FibrePoint> kNone;
  const Circuit* c = worst >= 0 ? &plan.circuits[worst] : nullptr;
  const std::vector<FibrePoint>& pts = c ? c->points : kNone;
  const double s_end = pts.empty() ? 1.0 : std::max(pts.back().s, 1e-9);
  auto px = [&](double s) { return ml + s / s_end * pw; };
  // The planned lambda where the plan uses friction on purpose.
  const FrictionFigures& ff = m.friction_turnarounds;
  const double planned = ff.planned ? std::max({ff.pass_lambda, ff.lambda[0], ff.lambda[1]}) : 0.0;

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << opts.width << "\" height=\""
    << height << "\" viewBox=\"0 0 " << opts.width << " " << height << "\" data-circuit=\"" << worst
    << "\" data-max=\"" << top_slip << "\">\n"
    << "<title>" << xml_escape("windplan fibre stability: " + plan.job_name) << "</title>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << opts.width << "\" height=\"" << height
    << "\" fill=\"white\"/>\n";
  char head[256];
  std::snprintf(head, sizeof head,
                ": circuit %d of %zu (the largest |k_g/k_n|: %.3f against mu %.2f%s)", worst,
                plan.circuits.size(), top_slip, mu, top_slip > mu ? ", slips" : ", holds");
  o << "<text x=\"" << ml << "\" y=\"24\" font-family=\"sans-serif\" font-size=\"15\">"
    << xml_escape(plan.job_name + head) << "</text>\n";

  struct Panel {
    const char* quantity;
    const char* label;
    double lo, hi;
    double FibrePoint::*field;
    const char* colour;
  };
  const double slip_hi = std::max({1.25 * mu, 1.05 * top_slip, 1.25 * planned, 0.05});
  const Panel panels[2] = {
      {"angle", "winding angle [deg]", 0.0, 90.0, &FibrePoint::winding_angle, "#1f77b4"},
      {"slippage", "|k_g/k_n|", 0.0, slip_hi, &FibrePoint::slippage, "#2ca02c"}};
  for (int p = 0; p < 2; ++p) {
    const Panel& pn = panels[p];
    const double top = mt + p * (ph + gap);
    auto py = [&](double v) {
      return top + ph - (std::clamp(v, pn.lo, pn.hi) - pn.lo) / (pn.hi - pn.lo) * ph;
    };
    o << "<g class=\"panel\" data-quantity=\"" << pn.quantity << "\" data-lo=\"" << pn.lo
      << "\" data-hi=\"" << pn.hi << "\" font-family=\"sans-serif\" font-size=\"10\" "
      << "fill=\"#333\">\n"
      << "<rect x=\"" << f2(ml) << "\" y=\"" << f2(top) << "\" width=\"" << f2(pw) << "\" height=\""
      << f2(ph) << "\" fill=\"none\" stroke=\"#333\" stroke-width=\"0.8\"/>\n"
      << "<text x=\"" << f2(ml) << "\" y=\"" << f2(top - 6) << "\" font-size=\"12\">"
      << xml_escape(pn.label) << "</text>\n";
    o << value_grid(pn.lo, pn.hi, ml, pw, py);
    if (c) {
      // Dwell arcs (held by pins or a ring) shaded; bridging points marked.
      for (const CircuitSegment& seg : c->segments) {
        if (seg.kind != CircuitSegment::Kind::Turnaround) continue;
        const double x0 = px(pts[seg.first].s), x1 = px(pts[seg.last].s);
        o << "<rect class=\"dwell\" x=\"" << f2(x0) << "\" y=\"" << f2(top) << "\" width=\""
          << f2(std::max(0.5, x1 - x0)) << "\" height=\"" << f2(ph)
          << "\" fill=\"#000\" fill-opacity=\"0.08\"/>\n";
      }
      if (p == 1) {
        for (std::size_t i = 0; i < pts.size(); ++i) {
          if (pts[i].k_n > 0.0) continue;
          o << "<line class=\"bridging\" x1=\"" << f2(px(pts[i].s)) << "\" y1=\"" << f2(top)
            << "\" x2=\"" << f2(px(pts[i].s)) << "\" y2=\"" << f2(top + ph)
            << "\" stroke=\"#ff7f0e\" stroke-width=\"0.5\"/>\n";
        }
      }
      o << "<polyline fill=\"none\" stroke=\"" << pn.colour << "\" stroke-width=\"1\" points=\""
        << envelope_points(
               pts.size(), [&](std::size_t i) { return pts[i].s; },
               [&](std::size_t i) { return std::clamp(pts[i].*pn.field, pn.lo, pn.hi); }, px, py,
               ml, cols)
        << "\"/>\n";
    }
    if (p == 1) {
      o << "<line class=\"mu\" data-value=\"" << mu << "\" x1=\"" << f2(ml) << "\" y1=\""
        << f2(py(mu)) << "\" x2=\"" << f2(ml + pw) << "\" y2=\"" << f2(py(mu))
        << "\" stroke=\"#d62728\" stroke-width=\"1.2\"/>\n"
        << "<text x=\"" << f2(ml + pw - 4) << "\" y=\"" << f2(py(mu) - 4)
        << "\" text-anchor=\"end\" fill=\"#d62728\">mu " << f2(mu) << ": above it the fibre "
        << "slips</text>\n";
      if (planned > 0.0) {
        o << "<line class=\"planned\" data-value=\"" << planned << "\" x1=\"" << f2(ml)
          << "\" y1=\"" << f2(py(planned)) << "\" x2=\"" << f2(ml + pw) << "\" y2=\""
          << f2(py(planned)) << "\" stroke=\"#555\" stroke-dasharray=\"6 4\" "
          << "stroke-width=\"1\"/>\n"
          << "<text x=\"" << f2(ml + 4) << "\" y=\"" << f2(py(planned) - 4) << "\">planned "
          << "friction " << f2(planned) << " (winding.slippage)</text>\n";
      }
    }
    o << "</g>\n";
  }
  const double bottom = mt + 2 * ph + gap;
  o << bottom_axis(s_end, bottom, ml, pw, px,
                   "fibre length along the circuit [mm] (grey: dwell arcs held by pins or a "
                   "ring; orange: k_n &lt;= 0, the fibre would bridge)")
    << "</svg>\n";
  return o.str();
}

}  // namespace windplan
