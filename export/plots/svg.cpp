#include "export/plots/svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <sstream>

#include "export/plots/svg_util.h"
#include "export/plots/viewer.h"

namespace windplan {

namespace {

constexpr double kLayerPalette[][3] = {
    {31, 119, 180}, {255, 127, 14},  {44, 160, 44},  {214, 39, 40},  {148, 103, 189},
    {140, 86, 75},  {227, 119, 194}, {23, 190, 207}, {188, 189, 34}, {127, 127, 127}};

std::string layer_colour(int l) {
  const auto& c = kLayerPalette[((l % 10) + 10) % 10];
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", int(c[0]), int(c[1]), int(c[2]));
  return buf;
}

std::string fmt1(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

// A curve in the plot's coordinates with its angle unwrapped (continuous, may leave [0, 360)).
struct Unwrapped {
  std::vector<Vec2> pts;  // (along mm, around deg unwrapped)
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;  // around range
  void add(const Vec2& q) {
    pts.push_back(q);
    lo = std::min(lo, q.y());
    hi = std::max(hi, q.y());
  }
};

// The representative of `deg` (mod 360) nearest to `ref`.
double near_to(double deg, double ref) { return deg + 360.0 * std::round((ref - deg) / 360.0); }

// Labels in lanes above the plot: the first lane where the text does not overlap another.
struct LabelLanes {
  std::vector<std::vector<std::pair<double, double>>> lanes;
  int place(double x0, double x1) {
    for (std::size_t i = 0;; ++i) {
      if (i == lanes.size()) lanes.emplace_back();
      bool free = true;
      for (const auto& iv : lanes[i])
        if (x0 < iv.second + 6 && iv.first < x1 + 6) free = false;
      if (free) {
        lanes[i].push_back({x0, x1});
        return static_cast<int>(i);
      }
    }
  }
};

}  // namespace

std::string development_svg(const WindingPlan& plan, const Unrolling& un, const SvgOptions& opts) {
  const bool axis_kind = un.kind() == Unrolling::Kind::Axis;
  const double w = plan.metrics.band_width;

  // Circuits: centre line and both band edges, unrolled and unwrapped.
  struct Band {
    Unwrapped centre, left, right;
  };
  std::vector<Band> bands(plan.circuits.size());
  for (std::size_t k = 0; k < plan.circuits.size(); ++k) {
    const Circuit& c = plan.circuits[k];
    const double wk = circuit_band_width(plan, static_cast<int>(k));  // its layer's band
    double ref = 0.0;
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const FibrePoint& p = c.points[i];
      Vec2 q = un.map(p.position, p.face);
      q.y() = i == 0 ? q.y() : near_to(q.y(), ref);
      ref = q.y();
      bands[k].centre.add(q);
      if (wk > 0.0) {
        Vec3 side = p.normal.cross(p.tangent);
        side = side.norm() > 0.0 ? Vec3(side.normalized() * (wk / 2.0)) : Vec3(Vec3::Zero());
        Vec2 a = un.map_offset(p.position, p.face, p.position + side),
             b = un.map_offset(p.position, p.face, p.position - side);
        a.y() = near_to(a.y(), ref);
        b.y() = near_to(b.y(), ref);
        bands[k].left.add(a);
        bands[k].right.add(b);
      }
    }
  }
  std::vector<Unwrapped> cuts(plan.cutlines.size());
  for (std::size_t k = 0; k < plan.cutlines.size(); ++k) {
    const CutLine& l = plan.cutlines[k];
    const std::size_t n = l.points.size() + (l.closed && l.points.size() > 2 ? 1 : 0);
    double ref = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      Vec2 q = un.map(l.points[i % l.points.size()]);
      q.y() = i == 0 ? q.y() : near_to(q.y(), ref);
      ref = q.y();
      cuts[k].add(q);
    }
  }

  // The along range: everything drawn, and the mandrel's ends.
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin;
  auto grow = [&](const Unwrapped& u) {
    for (const Vec2& q : u.pts) {
      xmin = std::min(xmin, q.x());
      xmax = std::max(xmax, q.x());
    }
  };
  for (const Band& b : bands) grow(b.centre), grow(b.left), grow(b.right);
  for (const Unwrapped& u : cuts) grow(u);
  if (axis_kind && !plan.profile.empty()) {
    xmin = std::min(xmin, plan.profile.axial.front());
    xmax = std::max(xmax, plan.profile.axial.back());
  }
  if (!axis_kind) {
    xmin = std::min(xmin, 0.0);
    xmax = std::max(xmax, un.length());
  }
  if (!(xmin < xmax)) {
    xmin = (std::isfinite(xmin) ? xmin : 0.0) - 1.0;
    xmax = xmin + 2.0;
  }
  const double ml = 70, mr = 250, mt = 100, mb = 58;
  const double pw = opts.width - ml - mr, ph = opts.height - mt - mb;
  auto px = [&](double x) { return ml + (x - xmin) / (xmax - xmin) * pw; };
  auto py = [&](double deg) { return mt + deg / 360.0 * ph; };

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
       "width=\""
    << opts.width << "\" height=\"" << opts.height << "\" viewBox=\"0 0 " << opts.width << " "
    << opts.height << "\">\n"
    << "<title>" << xml_escape("windplan development: " + plan.job_name) << "</title>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << opts.width << "\" height=\"" << opts.height
    << "\" fill=\"white\"/>\n"
    << "<text x=\"" << ml << "\" y=\"20\" font-family=\"sans-serif\" font-size=\"15\">"
    << xml_escape(plan.job_name) << ": " << plan.circuits.size() << " circuits, band " << f2(w)
    << " mm, cover factor " << f2(plan.metrics.cover_factor) << ", " << plan.cutlines.size()
    << " cut-lines"
    << (axis_kind ? " (unrolled about the spindle axis)"
                  : " (unrolled in the tube's own coordinates)")
    << "</text>\n";
  const CoverageReport& cov = plan.metrics.coverage;
  double sub_y = 36;
  if (cov.measured()) {
    o << "<text id=\"coverage\" x=\"" << ml << "\" y=\"" << sub_y
      << "\" font-family=\"sans-serif\" font-size=\"11\" fill=\""
      << (cov.bare_fraction > 0.0 ? "#b00000" : "#1a6e2e")
      << "\">measured coverage: " << xml_escape(cov.brief_report()) << "</text>\n";
    sub_y += 13;
  }
  if (!un.fallback_reason.empty()) {
    o << "<text x=\"" << ml << "\" y=\"" << sub_y
      << "\" font-family=\"sans-serif\" font-size=\"11\" "
      << "fill=\"#8a3b00\">" << xml_escape(un.fallback_reason) << "</text>\n";
  }
  o << "<defs><clipPath id=\"plot\"><rect x=\"" << f2(ml) << "\" y=\"" << f2(mt) << "\" width=\""
    << f2(pw) << "\" height=\"" << f2(ph) << "\"/></clipPath></defs>\n";

  // Grid and ticks.
  o << "<g id=\"grid\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#333\">\n";
  const double step = nice_step(xmax - xmin, 10);
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  for (double x = std::ceil(xmin / step) * step; x <= xmax + 1e-9 * step; x += step) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::fabs(x) < 1e-9 * step ? 0.0 : x);
    o << "<line x1=\"" << f2(px(x)) << "\" y1=\"" << f2(mt) << "\" x2=\"" << f2(px(x)) << "\" y2=\""
      << f2(mt + ph) << "\" stroke=\"#e4e4e4\" stroke-width=\"0.5\"/>\n"
      << "<text x=\"" << f2(px(x)) << "\" y=\"" << f2(mt + ph + 18) << "\" text-anchor=\"middle\">"
      << buf << "</text>\n";
  }
  for (int d = 0; d <= 360; d += 45) {
    o << "<line x1=\"" << f2(ml) << "\" y1=\"" << f2(py(d)) << "\" x2=\"" << f2(ml + pw)
      << "\" y2=\"" << f2(py(d)) << "\" stroke=\"#e4e4e4\" stroke-width=\"0.5\"/>\n"
      << "<text x=\"" << f2(ml - 8) << "\" y=\"" << f2(py(d) + 4) << "\" text-anchor=\"end\">" << d
      << "</text>\n";
  }
  o << "<text x=\"" << f2(ml + pw / 2) << "\" y=\"" << f2(opts.height - 14)
    << "\" text-anchor=\"middle\" font-size=\"13\">" << xml_escape(un.along_title()) << "</text>\n"
    << "<text x=\"18\" y=\"" << f2(mt + ph / 2) << "\" text-anchor=\"middle\" font-size=\"13\" "
    << "transform=\"rotate(-90 18 " << f2(mt + ph / 2) << ")\">" << xml_escape(un.around_title())
    << "</text>\n</g>\n";

  // Bands: polygons in <defs> (pixel x, unwrapped pixel y), placed every 360 deg by <use>.
  const std::vector<int> layers = circuit_layers(plan);
  const std::set<int> layer_set(layers.begin(), layers.end());
  const bool by_layer = layer_set.size() > 1;
  auto band_colour = [&](std::size_t k) {
    return by_layer ? layer_colour(layers[k]) : circuit_colour(static_cast<int>(k));
  };
  auto points_attr = [&](const std::vector<Vec2>& fwd, const std::vector<Vec2>& back,
                         const std::vector<std::size_t>& keep) {
    std::ostringstream s;
    bool first = true;
    for (std::size_t i : keep) {
      s << (first ? "" : " ") << f2(px(fwd[i].x())) << "," << f2(py(fwd[i].y()));
      first = false;
    }
    for (auto it = keep.rbegin(); it != keep.rend() && !back.empty(); ++it)
      s << " " << f2(px(back[*it].x())) << "," << f2(py(back[*it].y()));
    return s.str();
  };
  // Indices kept after thinning (moves under 0.7 px skipped; the last point always kept).
  auto thin = [&](const std::vector<Vec2>& pts) {
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (!keep.empty() && i + 1 < pts.size()) {
        const Vec2& a = pts[keep.back()];
        if (std::hypot(px(pts[i].x()) - px(a.x()), py(pts[i].y()) - py(a.y())) < 0.7) continue;
      }
      keep.push_back(i);
    }
    return keep;
  };
  auto copies = [&](double lo, double hi) {  // multiples n of 360 with [lo, hi] - 360 n on the plot
    std::vector<int> ns;
    for (int n = static_cast<int>(std::floor(lo / 360.0)) - 1;
         n <= static_cast<int>(std::ceil(hi / 360.0)) + 1; ++n)
      if (hi - 360.0 * n >= 0.0 && lo - 360.0 * n <= 360.0) ns.push_back(n);
    return ns;
  };
  o << "<defs>\n";
  for (std::size_t k = 0; k < bands.size(); ++k) {
    const Band& b = bands[k];
    if (b.centre.pts.size() < 2) continue;
    const std::vector<std::size_t> keep = thin(b.centre.pts);
    if (!b.left.pts.empty()) {
      o << "<polygon id=\"band-" << k << "\" class=\"band\" data-circuit=\""
        << plan.circuits[k].index << "\" data-layer=\"" << layers[k] << "\" points=\""
        << points_attr(b.left.pts, b.right.pts, keep) << "\"/>\n";
    }
    o << "<polyline id=\"path-" << k << "\" points=\"" << points_attr(b.centre.pts, {}, keep)
      << "\"/>\n";
  }
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    if (cuts[k].pts.size() < 2) continue;
    o << "<polyline id=\"cut-" << k << "\" points=\""
      << points_attr(cuts[k].pts, {}, thin(cuts[k].pts)) << "\"/>\n";
  }
  o << "</defs>\n";
  auto use = [&](const std::string& id, double lo, double hi, const std::string& style) {
    for (int n : copies(lo, hi)) {
      o << "<use xlink:href=\"#" << id << "\" y=\"" << f2(-n * ph) << "\" " << style << "/>\n";
    }
  };
  o << "<g id=\"bands\" clip-path=\"url(#plot)\">\n";
  for (std::size_t k = 0; k < bands.size(); ++k) {
    const Band& b = bands[k];
    if (b.centre.pts.size() < 2) continue;
    o << "<g class=\"circuit\" id=\"circuit-" << plan.circuits[k].index << "\">\n";
    if (!b.left.pts.empty()) {
      use("band-" + std::to_string(k), std::min(b.left.lo, b.right.lo),
          std::max(b.left.hi, b.right.hi),
          "fill=\"" + band_colour(k) + "\" fill-opacity=\"" + f2(opts.band_opacity) +
              "\" stroke=\"none\"");
    }
    use("path-" + std::to_string(k), b.centre.lo, b.centre.hi,
        "fill=\"none\" stroke=\"" + band_colour(k) + "\" stroke-width=\"0.6\"");
    o << "</g>\n";
  }
  o << "</g>\n<g id=\"cutlines\" clip-path=\"url(#plot)\">\n";
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    if (cuts[k].pts.size() < 2) continue;
    o << "<g class=\"cutline\" id=\"cutline-" << k << "\" data-name=\""
      << xml_escape(plan.cutlines[k].name) << "\">\n";
    use("cut-" + std::to_string(k), cuts[k].lo, cuts[k].hi,
        "fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"");
    o << "</g>\n";
  }
  o << "</g>\n";
  o << "<rect x=\"" << f2(ml) << "\" y=\"" << f2(mt) << "\" width=\"" << f2(pw) << "\" height=\""
    << f2(ph) << "\" fill=\"none\" stroke=\"#333\" stroke-width=\"1\"/>\n";

  // Marker lines with labels in lanes above the plot.
  struct Marker {
    double x;
    std::string style, label;
  };
  std::vector<Marker> markers;
  const std::string solid = "stroke=\"#888\" stroke-width=\"1.5\"";
  const std::string dash = "stroke=\"#999\" stroke-width=\"1\" stroke-dasharray=\"6 4\"";
  if (axis_kind) {
    if (!plan.profile.empty()) {
      for (double x : {plan.profile.axial.front(), plan.profile.axial.back()})
        markers.push_back({x, solid, "mandrel end " + f2(x) + " mm"});
    }
    const AxisFrame frame = make_axis_frame(plan.axis);
    double tmin = std::numeric_limits<double>::infinity(), tmax = -tmin;
    bool any_turn = false;
    for (const Circuit& c : plan.circuits)
      for (const CircuitSegment& s : c.segments) {
        if (s.kind != CircuitSegment::Kind::Turnaround) continue;
        for (int i = std::max(0, s.first); i <= s.last && i < int(c.points.size()); ++i) {
          const double x = frame.axial(c.points[i].position);
          any_turn = true;
          tmin = std::min(tmin, x);
          tmax = std::max(tmax, x);
        }
      }
    if (!any_turn)
      for (const Band& b : bands)
        for (const Vec2& q : b.centre.pts) {
          tmin = std::min(tmin, q.x());
          tmax = std::max(tmax, q.x());
        }
    if (std::isfinite(tmin)) {
      const std::string what = any_turn ? "turnaround " : "fibre end ";
      markers.push_back({tmin, dash, what + f2(tmin) + " mm"});
      if (tmax > tmin) markers.push_back({tmax, dash, what + f2(tmax) + " mm"});
    }
  } else {
    markers.push_back({0.0, solid, "end 0 (h = 0)"});
    markers.push_back({un.length(), solid, "end 1 (h = 1)"});
  }
  // Measured coverage stations: a bare one is a red dashed line with its figures. On a shape of
  // revolution a station is an axial position; off one, a level of the harmonic height
  // (planner/winding/coverage.h), drawn at along = level * L in the conformal unrolling.
  const std::string bare_style = "stroke=\"#c00000\" stroke-width=\"1.2\" stroke-dasharray=\"3 3\"";
  const bool levels = !axis_kind;
  const bool stations_drawn = cov.measured();
  auto station_x = [&](double station) { return levels ? station * un.length() : station; };
  if (stations_drawn) {
    for (const StationCoverage& st : cov.stations) {
      if (st.bare_fraction > 0.0) {
        markers.push_back(
            {station_x(st.station), bare_style, fmt1(100.0 * st.bare_fraction) + "% bare"});
      }
    }
  }
  std::sort(markers.begin(), markers.end(),
            [](const Marker& a, const Marker& b) { return a.x < b.x; });
  LabelLanes lanes;
  o << "<g id=\"labels\" font-family=\"sans-serif\" font-size=\"10\" fill=\"#555\">\n";
  for (const Marker& m : markers) {
    const double x = px(m.x);
    const double tw = 5.6 * static_cast<double>(m.label.size());
    const bool right = x > ml + pw / 2;
    const double x0 = right ? x - 3 - tw : x + 3, x1 = right ? x - 3 : x + 3 + tw;
    const int lane = std::min(lanes.place(x0, x1), 3);
    const double ty = mt - 8 - 13.0 * lane;
    o << "<line x1=\"" << f2(x) << "\" y1=\"" << f2(ty - 9) << "\" x2=\"" << f2(x) << "\" y2=\""
      << f2(mt + ph) << "\" " << m.style << "/>\n"
      << "<text x=\"" << f2(right ? x - 3 : x + 3) << "\" y=\"" << f2(ty) << "\" text-anchor=\""
      << (right ? "end" : "start") << "\">" << xml_escape(m.label) << "</text>\n";
  }
  o << "</g>\n";
  if (stations_drawn) {
    o << "<g id=\"coverage-stations\">\n";
    for (const StationCoverage& st : cov.stations) {
      const double x = px(station_x(st.station)), y = mt + ph + 1;
      o << "<path class=\"station\" data-station=\"" << f2(st.station) << "\" data-bare=\""
        << f2(100.0 * st.bare_fraction) << "\" d=\"M" << f2(x) << "," << f2(y)
        << " l-4,7 h8 z\" fill=\"" << (st.bare_fraction > 0.0 ? "#c00000" : "#1a9850") << "\"/>\n";
    }
    o << "</g>\n";
  }

  // Legend.
  const double lx = ml + pw + 18;
  double ly = mt + 4;
  o << "<g id=\"legend\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#222\">\n"
    << "<text x=\"" << f2(lx) << "\" y=\"" << f2(ly) << "\" font-weight=\"bold\">"
    << (by_layer ? "Layers" : "Circuits (band " + f2(w) + " mm)") << "</text>\n";
  ly += 8;
  auto swatch = [&](double x, double y, const std::string& fill, double op, const std::string& text,
                    const std::string& cls) {
    o << "<rect class=\"" << cls << "\" x=\"" << f2(x) << "\" y=\"" << f2(y) << "\" width=\"12\" "
      << "height=\"10\" fill=\"" << fill << "\" fill-opacity=\"" << f2(op)
      << "\" stroke=\"#999\" stroke-width=\"0.5\"/>\n"
      << "<text x=\"" << f2(x + 16) << "\" y=\"" << f2(y + 9) << "\">" << xml_escape(text)
      << "</text>\n";
  };
  if (by_layer) {
    for (int l : layer_set) {
      swatch(lx, ly, layer_colour(l), 1.0, layer_label(plan, l), "legend-layer");
      ly += 14;
    }
  } else if (plan.circuits.size() <= 48) {
    const std::size_t rows = (plan.circuits.size() + 2) / 3;
    for (std::size_t k = 0; k < plan.circuits.size(); ++k) {
      swatch(lx + 74.0 * static_cast<double>(k / std::max<std::size_t>(1, rows)),
             ly + 13.0 * static_cast<double>(k % std::max<std::size_t>(1, rows)),
             circuit_colour(static_cast<int>(k)), 1.0, std::to_string(plan.circuits[k].index),
             "legend-circuit");
    }
    ly += 13.0 * static_cast<double>(rows);
  } else {
    const double sw = 220.0 / static_cast<double>(plan.circuits.size());
    for (std::size_t k = 0; k < plan.circuits.size(); ++k) {
      o << "<rect class=\"legend-circuit\" x=\"" << f2(lx + sw * k) << "\" y=\"" << f2(ly)
        << "\" width=\"" << f2(sw + 0.3) << "\" height=\"10\" fill=\""
        << circuit_colour(static_cast<int>(k)) << "\"/>\n";
    }
    o << "<text x=\"" << f2(lx) << "\" y=\"" << f2(ly + 22) << "\">circuit "
      << plan.circuits.front().index << " ... " << plan.circuits.back().index
      << " in winding order</text>\n";
    ly += 28;
  }
  ly += 14;
  o << "<text x=\"" << f2(lx) << "\" y=\"" << f2(ly) << "\" font-weight=\"bold\">Coverage</text>\n";
  ly += 8;
  swatch(lx, ly, "white", 1.0, "bare: no band", "legend-coverage");
  ly += 14;
  swatch(lx, ly, "#555555", opts.band_opacity, "one band", "legend-coverage");
  ly += 14;
  const double two = 1.0 - (1.0 - opts.band_opacity) * (1.0 - opts.band_opacity);
  swatch(lx, ly, "#555555", two, "two or more: overlap", "legend-coverage");
  ly += 24;
  o << "<text x=\"" << f2(lx) << "\" y=\"" << f2(ly) << "\" font-weight=\"bold\">Lines</text>\n";
  ly += 8;
  auto line_key = [&](const std::string& style, const std::string& text) {
    o << "<line x1=\"" << f2(lx) << "\" y1=\"" << f2(ly + 5) << "\" x2=\"" << f2(lx + 24)
      << "\" y2=\"" << f2(ly + 5) << "\" " << style << "/>\n"
      << "<text x=\"" << f2(lx + 30) << "\" y=\"" << f2(ly + 9) << "\">" << text << "</text>\n";
    ly += 14;
  };
  line_key("stroke=\"black\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"", "cut-line");
  line_key(solid, axis_kind ? "mandrel end" : "end of the wound region");
  if (axis_kind) line_key(dash, "turnaround zone");
  line_key("stroke=\"#555\" stroke-width=\"0.6\"", "fibre centre line");
  if (stations_drawn) {
    o << "<path d=\"M" << f2(lx + 12) << "," << f2(ly + 1) << " l-4,7 h8 z\" fill=\"#1a9850\"/>\n"
      << "<path d=\"M" << f2(lx + 22) << "," << f2(ly + 1) << " l-4,7 h8 z\" fill=\"#c00000\"/>\n"
      << "<text x=\"" << f2(lx + 30) << "\" y=\"" << f2(ly + 9)
      << "\">measured station: covered / bare</text>\n";
    ly += 14;
    line_key(bare_style, "bare at a station (% of its loop)");
  }
  o << "</g>\n</svg>\n";
  return o.str();
}

}  // namespace windplan
