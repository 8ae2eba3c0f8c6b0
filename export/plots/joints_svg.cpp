#include "export/plots/joints_svg.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "export/plots/svg_util.h"

namespace windplan {

std::string joints_svg(const std::vector<double>& t, const std::vector<JointSeries>& joints,
                       const std::string& job_name, int width, int panel_height) {
  const double ml = 90, mr = 20, mt = 40, gap = 18, mb = 50;
  const int n = static_cast<int>(joints.size());
  const double ph = panel_height;
  const int height = static_cast<int>(mt + n * ph + std::max(0, n - 1) * gap + mb);
  const double pw = width - ml - mr;
  const double t_end = t.empty() ? 1.0 : std::max(t.back(), 1e-9);
  auto px = [&](double v) { return ml + v / t_end * pw; };
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height << "\">\n"
    << "<title>" << xml_escape("windplan robot joints: " + job_name) << "</title>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height
    << "\" fill=\"white\"/>\n"
    << "<text x=\"" << ml << "\" y=\"22\" font-family=\"sans-serif\" font-size=\"15\">"
    << xml_escape(job_name) << ": positioner and arm joints against time (" << t.size()
    << " targets, cycle " << f2(t.empty() ? 0.0 : t.back()) << " s)</text>\n";
  const int cols = std::max(1, static_cast<int>(pw));
  for (int k = 0; k < n; ++k) {
    const JointSeries& j = joints[k];
    const double top = mt + k * (ph + gap);
    double lo = 0.0, hi = 0.0;
    if (!j.values.empty()) {
      lo = *std::min_element(j.values.begin(), j.values.end());
      hi = *std::max_element(j.values.begin(), j.values.end());
    }
    if (!(hi - lo > 1e-9 * std::max(1.0, std::fabs(hi)))) {
      lo -= 1.0;
      hi += 1.0;
    }
    auto py = [&](double v) { return top + ph - (v - lo) / (hi - lo) * ph; };
    o << "<g class=\"panel\" data-joint=\"" << xml_escape(j.name)
      << "\" font-family=\"sans-serif\" font-size=\"10\" fill=\"#333\">\n"
      << "<rect x=\"" << f2(ml) << "\" y=\"" << f2(top) << "\" width=\"" << f2(pw) << "\" height=\""
      << f2(ph) << "\" fill=\"none\" stroke=\"#333\" stroke-width=\"0.8\"/>\n"
      << "<text x=\"12\" y=\"" << f2(top + ph / 2 + 4) << "\" font-size=\"13\">"
      << xml_escape(j.name) << " [deg]</text>\n";
    o << value_grid(lo, hi, ml, pw, py);
    for (double lim : {j.min, j.max}) {
      if (std::isfinite(lim) && lim >= lo && lim <= hi) {
        o << "<line x1=\"" << f2(ml) << "\" y1=\"" << f2(py(lim)) << "\" x2=\"" << f2(ml + pw)
          << "\" y2=\"" << f2(py(lim)) << "\" stroke=\"#d62728\" stroke-dasharray=\"4 3\"/>\n";
      }
    }
    o << "<polyline fill=\"none\" stroke=\"" << circuit_colour(k)
      << "\" stroke-width=\"1\" points=\""
      << envelope_points(
             std::min(t.size(), j.values.size()), [&](std::size_t i) { return t[i]; },
             [&](std::size_t i) { return j.values[i]; }, px, py, ml, cols);
    o << "\"/>\n</g>\n";
  }
  const double bottom = mt + n * ph + std::max(0, n - 1) * gap;
  o << bottom_axis(t_end, bottom, ml, pw, px, "time t [s] (dashed: joint limits)") << "</svg>\n";
  return o.str();
}

}  // namespace windplan
