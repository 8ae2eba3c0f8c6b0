#include "planner/mandrel/tube_spine.h"

#include <algorithm>

#include "geometry/base/errors.h"

namespace windplan {

TubeSpine mandrel_tube_spine(const Mandrel& md, const MandrelOptions& options) {
  return tube_spine(md.winding, md.axis, options);
}

TubeSpine tube_spine(const WindingSurface& ws, const SpindleAxis& axis,
                     const MandrelOptions& options) {
  TubeSpine t;
  const std::array<std::vector<int>, 2> loops{ws.loops[0].vertices, ws.loops[1].vertices};
  if (options.source == "bent_tube") {
    std::vector<TubeBend> bends;
    for (const BendParams& b : options.bent_tube.bends) {
      bends.push_back({b.angle, b.radius, b.plane_angle});
    }
    t.exact = std::make_shared<const TubeCentreLine>(options.bent_tube.radius,
                                                     options.bent_tube.segments, bends);
    std::vector<Vec3> pts = t.exact->polyline(90);
    // Drop repeated points (a zero-length segment) before building the spine.
    std::vector<Vec3> clean;
    for (const Vec3& p : pts) {
      if (clean.empty() || (p - clean.back()).norm() > 1e-9) clean.push_back(p);
    }
    std::array<Vec3, 2> c;
    for (int e = 0; e < 2; ++e) {
      std::vector<Vec3> lp;
      for (int v : loops[e]) lp.push_back(ws.mesh.position(v));
      c[e] = loop_centroid(lp);
    }
    if (clean.size() >= 2) {
      if ((clean.front() - c[0]).norm() > (clean.back() - c[0]).norm()) {
        std::reverse(clean.begin(), clean.end());
      }
      Spine sp = spine_from_polyline(clean);
      double d0 = 0.0, d1 = 0.0;
      const double s0 = sp.project(c[0], &d0), s1 = sp.project(c[1], &d1);
      // Ends on sections inside the tube (mandrel.region.centre_line): the line between them.
      const double tol = 1e-6 * sp.length();
      if (std::max(d0, d1) <= 0.02 * options.bent_tube.radius && s1 > s0 &&
          (s0 > tol || s1 < sp.length() - tol)) {
        std::vector<Vec3> part{sp.point(s0)};
        for (std::size_t i = 0; i < sp.points.size(); ++i) {
          if (sp.s[i] > s0 + tol && sp.s[i] < s1 - tol) part.push_back(sp.points[i]);
        }
        part.push_back(sp.point(s1));
        sp = spine_from_polyline(part);
      }
      if (std::max(d0, d1) <= 0.02 * options.bent_tube.radius) {
        t.spine = std::move(sp);
        t.source = "bent_tube centre line";
        t.summary.sections = static_cast<int>(t.spine.points.size());
        t.summary.mean_radius = options.bent_tube.radius;
        return t;
      }
    }
  }
  try {
    SpineResult r = extract_spine(ws.mesh, loops, axis, {}, "tube centre line");
    t.spine = std::move(r.spine);
    t.summary = r.summary;
    t.source = "section centroids";
  } catch (const InputError& e) {
    t.why = e.what();
  }
  return t;
}

}  // namespace windplan
