#include "export/files/laminate_profiles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

namespace {

void check(const LaminateProfiles& p) {
  const std::size_t n = p.mandrel.points.size();
  if (p.names.size() != p.thickness.size() || p.names.size() != p.surfaces.size()) {
    throw InputError("laminate profiles: names, thickness and surfaces differ in count");
  }
  for (std::size_t k = 0; k < p.surfaces.size(); ++k) {
    if (p.surfaces[k].points.size() != n || p.thickness[k].thickness.size() != n) {
      throw InputError("laminate profiles: layer " + std::to_string(k) +
                       " does not have the mandrel meridian's " + std::to_string(n) + " points");
    }
  }
}

// Golden-angle hues, as development.svg colours its circuits.
std::string colour(std::size_t k) {
  const double hue = std::fmod(137.50776405 * static_cast<double>(k), 360.0);
  return "hsl(" + format_fixed(hue, 1) + ",70%,40%)";
}

}  // namespace

CsvTable laminate_profiles_table(const LaminateProfiles& p) {
  check(p);
  CsvTable t;
  t.header = {"surface",     "index",          "s [mm]",    "axial [mm]",
              "radius [mm]", "thickness [mm]", "total [mm]"};
  const std::size_t n = p.mandrel.points.size();
  const bool alt = p.alternative.size() == p.surfaces.size() && !p.alternative.empty();
  if (alt) t.header.push_back("thickness " + p.alternative_name + " [mm]");
  std::vector<double> total(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& q = p.mandrel.points[i];
    t.rows.push_back({0.0, static_cast<double>(i), p.mandrel.s[i], q.x(), q.y(), 0.0, 0.0});
    if (alt) t.rows.back().push_back(0.0);
  }
  for (std::size_t k = 0; k < p.surfaces.size(); ++k) {
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2& q = p.surfaces[k].points[i];
      const double th = p.thickness[k].thickness[i];
      total[i] += th;
      t.rows.push_back({static_cast<double>(k + 1), static_cast<double>(i), p.mandrel.s[i], q.x(),
                        q.y(), th, total[i]});
      if (alt) t.rows.back().push_back(p.alternative[k].thickness[i]);
    }
  }
  return t;
}

std::string laminate_profiles_svg(const LaminateProfiles& p, int width, int height) {
  check(p);
  const std::size_t n = p.mandrel.points.size();
  const double margin = 60.0, gap = 50.0;
  const double top_h = 0.55 * (height - 2 * margin - gap),
               bot_h = height - 2 * margin - gap - top_h;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, r1 = 0.0;
  auto extend = [&](const MeridianPolyline& m) {
    for (const Vec2& q : m.points) {
      x0 = std::min(x0, q.x());
      x1 = std::max(x1, q.x());
      r1 = std::max(r1, q.y());
    }
  };
  extend(p.mandrel);
  for (const MeridianPolyline& m : p.surfaces) extend(m);
  if (!(x1 > x0)) x1 = x0 + 1.0;
  if (!(r1 > 0.0)) r1 = 1.0;
  const double plot_w = width - 2 * margin;
  // Top panel at true scale: one mm per unit both ways.
  const double scale = std::min(plot_w / (x1 - x0), top_h / r1);
  auto top = [&](const Vec2& q) {
    return Vec2(margin + (q.x() - x0) * scale, margin + top_h - q.y() * scale);
  };
  std::vector<double> total(n, 0.0), total_alt(n, 0.0);
  std::vector<std::vector<double>> cumulative, cumulative_alt;
  const bool alt = p.alternative.size() == p.surfaces.size() && !p.alternative.empty();
  double tmax = 0.0;
  for (std::size_t k = 0; k < p.surfaces.size(); ++k) {
    for (std::size_t i = 0; i < n; ++i) total[i] += p.thickness[k].thickness[i];
    cumulative.push_back(total);
    tmax = std::max(tmax, *std::max_element(total.begin(), total.end()));
    if (alt) {
      for (std::size_t i = 0; i < n; ++i) total_alt[i] += p.alternative[k].thickness[i];
      cumulative_alt.push_back(total_alt);
      tmax = std::max(tmax, *std::max_element(total_alt.begin(), total_alt.end()));
    }
  }
  if (!(tmax > 0.0)) tmax = 1.0;
  const double bot_y0 = margin + top_h + gap;
  auto bottom = [&](double x, double t) {
    return Vec2(margin + (x - x0) / (x1 - x0) * plot_w, bot_y0 + bot_h - t / tmax * bot_h);
  };
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << margin << "\" y=\"" << margin - 20
    << "\">Meridian profiles (axial position x against radius r, true scale, mm)</text>\n"
    << "<text x=\"" << margin << "\" y=\"" << bot_y0 - 10 << "\">Cumulative thickness (mm, 0 to "
    << format_fixed(tmax, 3) << ") against the mandrel's axial position</text>\n";
  if (alt) {
    o << "<text x=\"" << margin << "\" y=\"" << format_fixed(bot_y0 + 6.0, 2)
      << "\" font-size=\"11\">solid: the job's dome model; dashed: " << p.alternative_name
      << "</text>\n";
  }
  auto polyline = [&](const std::vector<Vec2>& pts, const std::string& stroke, double w,
                      bool dashed = false) {
    o << "<polyline fill=\"none\" stroke=\"" << stroke << "\" stroke-width=\"" << format_fixed(w, 1)
      << (dashed ? "\" stroke-dasharray=\"5,3" : "") << "\" points=\"";
    for (std::size_t i = 0; i < pts.size(); ++i) {
      o << (i ? " " : "") << format_fixed(pts[i].x(), 2) << "," << format_fixed(pts[i].y(), 2);
    }
    o << "\"/>\n";
  };
  std::vector<Vec2> pts;
  for (const Vec2& q : p.mandrel.points) pts.push_back(top(q));
  polyline(pts, "#888888", 2.0);
  for (std::size_t k = 0; k < p.surfaces.size(); ++k) {
    pts.clear();
    for (const Vec2& q : p.surfaces[k].points) pts.push_back(top(q));
    polyline(pts, colour(k + 1), 1.0);
    pts.clear();
    for (std::size_t i = 0; i < n; ++i) {
      pts.push_back(bottom(p.mandrel.points[i].x(), cumulative[k][i]));
    }
    polyline(pts, colour(k + 1), 1.5);
    if (alt) {
      pts.clear();
      for (std::size_t i = 0; i < n; ++i) {
        pts.push_back(bottom(p.mandrel.points[i].x(), cumulative_alt[k][i]));
      }
      polyline(pts, colour(k + 1), 1.0, true);
    }
    o << "<text x=\"" << format_fixed(width - margin - 150.0, 2) << "\" y=\""
      << format_fixed(bot_y0 + 16.0 * static_cast<double>(k + 1), 2) << "\" fill=\""
      << colour(k + 1) << "\">" << k + 1 << ": " << p.names[k] << "</text>\n";
  }
  // Axes of the bottom panel.
  o << "<line x1=\"" << margin << "\" y1=\"" << format_fixed(bot_y0 + bot_h, 2) << "\" x2=\""
    << format_fixed(margin + plot_w, 2) << "\" y2=\"" << format_fixed(bot_y0 + bot_h, 2)
    << "\" stroke=\"black\"/>\n"
    << "<text x=\"" << margin << "\" y=\"" << format_fixed(bot_y0 + bot_h + 16.0, 2)
    << "\">x = " << format_fixed(x0, 1) << " mm</text>\n"
    << "<text x=\"" << format_fixed(margin + plot_w - 90.0, 2) << "\" y=\""
    << format_fixed(bot_y0 + bot_h + 16.0, 2) << "\">x = " << format_fixed(x1, 1) << " mm</text>\n"
    << "</svg>\n";
  return o.str();
}

}  // namespace windplan
