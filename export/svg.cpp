#include "export/svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "export/kinematics.h"

namespace windplan {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string f2(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.2f", v + 0.0);
  return std::string(buf) == "-0.00" ? "0.00" : buf;
}

std::string escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20) o += c;
    }
  }
  return o;
}

// Golden-angle hue, fixed saturation/lightness, as #rrggbb.
std::string colour(int k) {
  const double h = std::fmod(k * 137.50776405, 360.0) / 60.0;
  const double s = 0.75, l = 0.42;
  const double c = (1.0 - std::fabs(2.0 * l - 1.0)) * s;
  const double x = c * (1.0 - std::fabs(std::fmod(h, 2.0) - 1.0));
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0:
      r = c;
      g = x;
      break;
    case 1:
      r = x;
      g = c;
      break;
    case 2:
      g = c;
      b = x;
      break;
    case 3:
      g = x;
      b = c;
      break;
    case 4:
      r = x;
      b = c;
      break;
    default:
      r = c;
      b = x;
      break;
  }
  const double m = l - c / 2.0;
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround((r + m) * 255)),
                static_cast<int>(std::lround((g + m) * 255)),
                static_cast<int>(std::lround((b + m) * 255)));
  return buf;
}

double nice_step(double span, int target) {
  const double raw = span / std::max(1, target);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10.0 * p;
}

}  // namespace

std::string development_svg(const WindingPlan& plan, const SvgOptions& opts) {
  const AxisFrame frame = make_axis_frame(plan.axis);
  auto theta_deg = [&](const Vec3& p) {
    double t = frame.angle(p) * 180.0 / kPi;
    if (t < 0.0) t += 360.0;
    if (t >= 360.0) t -= 360.0;
    return t;
  };
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin;
  auto grow = [&](double x) {
    xmin = std::min(xmin, x);
    xmax = std::max(xmax, x);
  };
  for (const Circuit& c : plan.circuits)
    for (const FibrePoint& p : c.points) grow(frame.axial(p.position));
  for (const CutLine& l : plan.cutlines)
    for (const Vec3& p : l.points) grow(frame.axial(p));
  if (!plan.profile.empty()) {
    grow(plan.profile.axial.front());
    grow(plan.profile.axial.back());
  }
  if (!(xmin < xmax)) {
    xmin = (std::isfinite(xmin) ? xmin : 0.0) - 1.0;
    xmax = xmin + 2.0;
  }
  const double ml = 80, mr = 30, mt = 50, mb = 60;
  const double pw = opts.width - ml - mr, ph = opts.height - mt - mb;
  auto px = [&](double x) { return ml + (x - xmin) / (xmax - xmin) * pw; };
  auto py = [&](double deg) { return mt + deg / 360.0 * ph; };

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << opts.width << "\" height=\""
    << opts.height << "\" viewBox=\"0 0 " << opts.width << " " << opts.height << "\">\n"
    << "<title>" << escape("windplan development: " + plan.job_name) << "</title>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << opts.width << "\" height=\"" << opts.height
    << "\" fill=\"white\"/>\n"
    << "<text x=\"" << ml << "\" y=\"22\" font-family=\"sans-serif\" font-size=\"15\">"
    << escape(plan.job_name) << ": " << plan.circuits.size() << " circuits, "
    << plan.cutlines.size()
    << " cut-lines (unrolled: axial position vs angle about the "
       "spindle axis)</text>\n";
  // Frame, grid and tick labels.
  o << "<g font-family=\"sans-serif\" font-size=\"11\" fill=\"#333\">\n"
    << "<rect x=\"" << f2(ml) << "\" y=\"" << f2(mt) << "\" width=\"" << f2(pw) << "\" height=\""
    << f2(ph) << "\" fill=\"none\" stroke=\"#333\" stroke-width=\"1\"/>\n";
  const double step = nice_step(xmax - xmin, 10);
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  auto tick_label = [&](double x) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::fabs(x) < 1e-9 * step ? 0.0 : x);
    return std::string(buf);
  };
  for (double x = std::ceil(xmin / step) * step; x <= xmax + 1e-9 * step; x += step) {
    o << "<line x1=\"" << f2(px(x)) << "\" y1=\"" << f2(mt) << "\" x2=\"" << f2(px(x)) << "\" y2=\""
      << f2(mt + ph) << "\" stroke=\"#e4e4e4\" stroke-width=\"0.5\"/>\n"
      << "<text x=\"" << f2(px(x)) << "\" y=\"" << f2(mt + ph + 16) << "\" text-anchor=\"middle\">"
      << tick_label(x) << "</text>\n";
  }
  for (int d = 0; d <= 360; d += 45) {
    o << "<line x1=\"" << f2(ml) << "\" y1=\"" << f2(py(d)) << "\" x2=\"" << f2(ml + pw)
      << "\" y2=\"" << f2(py(d)) << "\" stroke=\"#e4e4e4\" stroke-width=\"0.5\"/>\n"
      << "<text x=\"" << f2(ml - 6) << "\" y=\"" << f2(py(d) + 4) << "\" text-anchor=\"end\">" << d
      << "</text>\n";
  }
  o << "<text x=\"" << f2(ml + pw / 2) << "\" y=\"" << f2(opts.height - 18)
    << "\" text-anchor=\"middle\" font-size=\"13\">axial position x [mm]</text>\n"
    << "<text x=\"20\" y=\"" << f2(mt + ph / 2) << "\" text-anchor=\"middle\" font-size=\"13\" "
    << "transform=\"rotate(-90 20 " << f2(mt + ph / 2) << ")\">angle about spindle axis [deg]"
    << "</text>\n</g>\n";

  // Mandrel ends and turnaround zones.
  // Labels of the right half are anchored at their end so that they stay inside the image.
  auto vline = [&](double x, const std::string& style, const std::string& label, double ty) {
    const bool right = px(x) > ml + pw / 2;
    o << "<line x1=\"" << f2(px(x)) << "\" y1=\"" << f2(mt) << "\" x2=\"" << f2(px(x)) << "\" y2=\""
      << f2(mt + ph) << "\" " << style << "/>\n"
      << "<text x=\"" << f2(px(x) + (right ? -3 : 3)) << "\" y=\"" << f2(ty)
      << "\" font-family=\"sans-serif\" font-size=\"10\" fill=\"#555\" text-anchor=\""
      << (right ? "end" : "start") << "\">" << escape(label) << "</text>\n";
  };
  if (!plan.profile.empty()) {
    const std::string solid = "stroke=\"#888\" stroke-width=\"1.5\"";
    vline(plan.profile.axial.front(), solid,
          "mandrel end " + f2(plan.profile.axial.front()) + " mm", mt + ph - 6);
    vline(plan.profile.axial.back(), solid, "mandrel end " + f2(plan.profile.axial.back()) + " mm",
          mt + ph - 6);
  }
  double tmin = std::numeric_limits<double>::infinity(), tmax = -tmin;
  bool any_turn = false;
  for (const Circuit& c : plan.circuits) {
    for (const CircuitSegment& s : c.segments) {
      if (s.kind != CircuitSegment::Kind::Turnaround) continue;
      for (int i = std::max(0, s.first); i <= s.last && i < static_cast<int>(c.points.size());
           ++i) {
        const double x = frame.axial(c.points[i].position);
        any_turn = true;
        tmin = std::min(tmin, x);
        tmax = std::max(tmax, x);
      }
    }
  }
  if (!any_turn) {
    for (const Circuit& c : plan.circuits)
      for (const FibrePoint& p : c.points) {
        tmin = std::min(tmin, frame.axial(p.position));
        tmax = std::max(tmax, frame.axial(p.position));
      }
  }
  if (std::isfinite(tmin)) {
    const std::string dash = "stroke=\"#999\" stroke-width=\"1\" stroke-dasharray=\"6 4\"";
    const std::string what = any_turn ? "turnaround " : "fibre end ";
    vline(tmin, dash, what + f2(tmin) + " mm", mt - 6);
    if (tmax > tmin) vline(tmax, dash, what + f2(tmax) + " mm", mt - 6);
  }

  // A polyline in the (x, theta) plane, split at the seam and thinned to half a pixel.
  auto draw = [&](const std::vector<Vec3>& pts, bool closed, const std::string& style) {
    if (pts.empty()) return;
    std::vector<std::vector<Vec2>> pieces(1);
    auto add = [&](const Vec2& q) {
      auto& cur = pieces.back();
      if (!cur.empty() && (cur.back() - q).norm() < 0.5) return;
      cur.push_back(q);
    };
    const std::size_t n = pts.size() + (closed && pts.size() > 2 ? 1 : 0);
    double px_prev = 0, th_prev = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = pts[i % pts.size()];
      const double x = frame.axial(p), th = theta_deg(p);
      if (i > 0) {
        double d = th - th_prev;
        if (std::fabs(d) > 180.0) {
          // Crosses the seam: finish at the seam on one side and restart on the other.
          const double up = d < 0.0 ? 360.0 : 0.0;  // seam value on the previous side
          const double unwrapped = d < 0.0 ? th + 360.0 : th - 360.0;
          const double f = (up - th_prev) / (unwrapped - th_prev);
          const double xs = px_prev + f * (x - px_prev);
          add(Vec2(px(xs), py(up)));
          pieces.emplace_back();
          add(Vec2(px(xs), py(360.0 - up)));
        }
      }
      add(Vec2(px(x), py(th)));
      px_prev = x;
      th_prev = th;
    }
    for (const auto& piece : pieces) {
      if (piece.size() < 2) continue;
      o << "<polyline " << style << " points=\"";
      for (std::size_t i = 0; i < piece.size(); ++i) {
        o << (i ? " " : "") << f2(piece[i].x()) << "," << f2(piece[i].y());
      }
      o << "\"/>\n";
    }
  };
  for (std::size_t k = 0; k < plan.circuits.size(); ++k) {
    const Circuit& c = plan.circuits[k];
    std::vector<Vec3> pts;
    for (const FibrePoint& p : c.points) pts.push_back(p.position);
    o << "<g id=\"circuit-" << c.index << "\">\n";
    draw(pts, false,
         "fill=\"none\" stroke=\"" + colour(static_cast<int>(k)) + "\" stroke-width=\"1.2\"");
    o << "</g>\n";
  }
  for (std::size_t k = 0; k < plan.cutlines.size(); ++k) {
    o << "<g id=\"cutline-" << k << "\">\n";
    draw(plan.cutlines[k].points, plan.cutlines[k].closed,
         "fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"");
    o << "</g>\n";
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace windplan
