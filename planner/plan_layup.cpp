#include "planner/plan_layup.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/mesh/closest_point.h"
#include "planner/cutlines/cutlines.h"
#include "planner/layup/dome_thickness.h"
#include "planner/layup/hoop.h"
#include "planner/winding/clairaut.h"
#include "planner/winding/fibre_metrics.h"
#include "planner/winding/helix.h"

namespace windplan {

namespace {

// A built surface as a mandrel for plan_winding: the whole mesh is the wound region.
Mandrel built_mandrel(const Mandrel& md, Mesh mesh, bool revolution, RadiusProfile profile) {
  Mandrel m;
  m.winding = extract_winding_surface(mesh, std::vector<char>(mesh.num_faces(), 1), md.axis);
  m.mesh = std::move(mesh);
  m.axis = md.axis;
  m.axis_source = md.axis_source;
  m.revolution = revolution;
  m.profile = std::move(profile);
  m.description = "the surface built by the layers under it";
  return m;
}

WindingSurface whole_surface(const Mesh& mesh, const SpindleAxis& axis) {
  return extract_winding_surface(mesh, std::vector<char>(mesh.num_faces(), 1), axis);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  return v[m];
}

// Pass points (not turnarounds) of a layer's circuits.
template <class F>
void for_pass_points(const std::vector<Circuit>& circuits, F f) {
  for (const Circuit& c : circuits) {
    for (const CircuitSegment& sg : c.segments) {
      if (sg.kind != CircuitSegment::Kind::Pass) continue;
      // A point shared with a neighbouring turnaround carries that arc's figures: left out.
      const int n = static_cast<int>(c.points.size());
      for (int i = sg.first + (sg.first > 0); i <= sg.last - (sg.last + 1 < n); ++i) {
        f(c.points[i]);
      }
    }
  }
}

int nearest_axial(const MeridianPolyline& m, double x) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(m.points.size()); ++i) {
    if (std::abs(m.points[i].x() - x) < std::abs(m.points[best].x() - x)) best = i;
  }
  return best;
}

// The thickness a layer leaves on each face of `mesh` from the band centre line length in each
// face: the band volume t B L_f spread over the faces within B/2 (centroid to centroid, reached
// across edges) in proportion to their area, so that faces smaller than the band do not take all
// of it; the total volume is kept.
std::vector<double> band_spread_thickness(const Mesh& mesh, const std::vector<double>& length,
                                          double band_width, double band_thickness) {
  const int nf = mesh.num_faces();
  std::vector<double> volume(nf, 0.0);
  std::vector<int> stamp(nf, -1), around;
  for (int f = 0; f < nf; ++f) {
    if (!(length[f] > 0.0)) continue;
    const Vec3 c = mesh.face_centroid(f);
    around.assign(1, f);
    stamp[f] = f;
    double area = 0.0;
    for (std::size_t i = 0; i < around.size(); ++i) {
      const int g = around[i];
      area += mesh.face_area(g);
      for (int k = 0; k < 3; ++k) {
        const int h = mesh.twin(mesh.face_halfedge(g) + k);
        const int n = mesh.face(h);
        if (n < 0 || stamp[n] == f) continue;
        stamp[n] = f;
        if ((mesh.face_centroid(n) - c).norm() <= 0.5 * band_width) around.push_back(n);
      }
    }
    const double v = band_thickness * band_width * length[f];
    for (int g : around) volume[g] += v * mesh.face_area(g) / area;
  }
  std::vector<double> t(nf, 0.0);
  for (int f = 0; f < nf; ++f) t[f] = volume[f] / mesh.face_area(f);
  return t;
}

// The outer surface's profile as a clearance envelope on the stations of the mandrel's own
// profile (a few hundred: the machine's envelope is evaluated per point, and the built meridian
// has thousands): at each station the largest radius of the surface within the neighbouring
// stations, so that the envelope never cuts into the part.
RadiusProfile envelope_profile(const RadiusProfile& surface, const RadiusProfile& stations) {
  if (stations.axial.size() < 2) return surface;
  RadiusProfile e;
  e.axial = stations.axial;
  e.radius.assign(e.axial.size(), 0.0);
  const std::size_t n = e.axial.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double lo = e.axial[i > 0 ? i - 1 : 0], hi = e.axial[i + 1 < n ? i + 1 : n - 1];
    double r = surface.at(e.axial[i]);
    for (std::size_t j = 0; j < surface.axial.size(); ++j) {
      if (surface.axial[j] >= lo && surface.axial[j] <= hi) r = std::max(r, surface.radius[j]);
    }
    e.radius[i] = std::max(r, stations.radius[i]);
  }
  return e;
}

}  // namespace

Mesh revolve_meridian(const MeridianPolyline& m, const SpindleAxis& axis, double edge) {
  if (!(edge > 0.0)) throw InputError("revolve: edge length must be > 0 mm");
  double rmax = 0.0;
  for (const Vec2& p : m.points) rmax = std::max(rmax, p.y());
  const int n_edge = static_cast<int>(std::ceil(2.0 * M_PI * rmax / edge));
  const int n = std::clamp(n_edge, 48, 512);
  // Rings no farther apart than the spacing around when `edge` is longer than that: a pipe's
  // mesh has triangles from end to end (edge 150 mm and more), and rings that far apart made
  // the built surface a double cone, 1.2 mm under the laminate at the ends.
  const double along = n_edge < 48 ? 2.0 * M_PI * rmax / 48 : edge;
  std::vector<int> rings{0};
  for (int i = 1; i + 1 < static_cast<int>(m.points.size()); ++i) {
    if (m.s[i] - m.s[rings.back()] >= along && m.s.back() - m.s[i] >= 0.5 * along)
      rings.push_back(i);
  }
  rings.push_back(static_cast<int>(m.points.size()) - 1);
  const Vec3 d = axis.direction.normalized();
  const Vec3 e1 = (std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(d).normalized();
  const Vec3 e2 = d.cross(e1);
  TriangleSoup s;
  for (int j : rings) {
    const Vec2& p = m.points[j];
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * M_PI * i / n;
      s.points.push_back(axis.origin + p.x() * d + p.y() * (std::cos(t) * e1 + std::sin(t) * e2));
    }
  }
  auto id = [n](int i, int j) { return j * n + (i % n); };
  for (int j = 0; j + 1 < static_cast<int>(rings.size()); ++j) {
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return Mesh(std::move(s));
}

RadiusProfile forward_profile(const MeridianPolyline& m) {
  RadiusProfile p;
  for (const Vec2& q : m.points) {
    if (!p.axial.empty() && !(q.x() > p.axial.back())) continue;
    p.axial.push_back(q.x());
    p.radius.push_back(q.y());
  }
  return p;
}

std::vector<const Mesh*> layup_circuit_surfaces(const LayupResult& result) {
  std::vector<const Mesh*> out;
  for (const LayupLayer& L : result.layers)
    out.insert(out.end(), L.circuits.size(), L.surface.get());
  return out;
}

LayupResult plan_layup(const Job& job, const PipelineOptions& options) {
  using clock = std::chrono::steady_clock;
  LayupResult R;
  std::vector<StageTiming> timings;
  auto stage = [&](const std::string& name, clock::time_point t0) {
    timings.push_back({name, std::chrono::duration<double>(clock::now() - t0).count()});
    if (options.on_stage) options.on_stage(timings.back());
  };
  auto t0 = clock::now();
  if (options.on_stage_start) options.on_stage_start("mandrel");
  R.mandrel = build_mandrel(job);
  stage("mandrel", t0);
  if (options.on_mandrel) options.on_mandrel(R.mandrel);
  const Mandrel& md = R.mandrel;
  const WindingSurface& ws = md.winding;
  const SpindleAxis& axis = md.axis;
  R.revolution = md.revolution;
  const std::vector<LayerOptions> layers = effective_layers(job.layers, job.winding);
  const double edge = ws.mesh.edge_length_stats()[1];

  // The current surface: a meridian (revolution) or a winding surface (otherwise).
  MeridianPolyline surface;
  std::pair<double, double> cylinder{0.0, 0.0};
  if (R.revolution) {
    const RadiusProfile mp = meridian_profile(ws.mesh, axis, ws.loops[0].axial, ws.loops[1].axial);
    double narrowest = layers.front().band_width();
    for (const LayerOptions& L : layers) narrowest = std::min(narrowest, L.band_width());
    R.profiles.mandrel =
        MeridianPolyline::from_profile(mp).resampled(std::max(0.25, narrowest / 4));
    surface = R.profiles.mandrel;
    cylinder = cylinder_range(mp);
  }
  WindingSurface built;  // off revolution: the current surface when it is not the mandrel's

  // design.turnaround_stagger: helical layer h turns around h x stagger band widths outward.
  int helical_index = 0;
  double opening = 0.0;  // the larger polar-opening radius of the mandrel's meridian
  if (R.revolution) {
    opening = std::max(R.profiles.mandrel.points.front().y(), R.profiles.mandrel.points.back().y());
  }
  bool have_metrics = false;
  PlanMetrics metrics;                // the innermost helical layer's
  std::vector<std::string> warnings;  // every layer's
  for (std::size_t k = 0; k < layers.size(); ++k) {
    t0 = clock::now();
    const LayerOptions& L = layers[k];
    const std::string what = "layers[" + std::to_string(k) + "]";
    if (options.on_stage_start) options.on_stage_start(L.name);
    LayupLayer out;
    out.options = L;
    LayerSummary& S = out.summary;
    S.name = L.name;
    S.kind = to_string(L.kind);
    S.band_width = L.band_width();
    S.band_thickness = job.material.thickness(S.band_width);
    const double t_band = S.band_thickness;
    LayerThickness th;
    // The surface this layer is wound on when it is not the mandrel: the laminate under it.
    std::shared_ptr<const Mesh> under;
    if (k > 0) {
      under = R.revolution ? std::make_shared<const Mesh>(revolve_meridian(surface, axis, edge))
                           : std::make_shared<const Mesh>(built.mesh);
      if (options.on_layer_surface) {
        options.on_layer_surface(*under, what + " (" + L.name + ")");
      }
    }
    if (L.kind == LayerKind::Hoop) {
      if (!R.revolution) {
        throw InputError(what +
                         ": a hoop layer needs a mandrel that is a shape of revolution "
                         "(this one is not: " +
                         md.axis_source + ")");
      }
      HoopOptions h = L.hoop;
      if (!h.has_range()) std::tie(h.x0, h.x1) = cylinder;
      const HoopLayer hl = plan_hoop_layer(forward_profile(surface), axis, h, what);
      out.circuits = hl.circuits;
      if (k > 0) out.surface = under;
      th = hoop_layer_thickness(surface, hl.x0, hl.x1, hl.pitch, S.band_width, t_band, h.passes);
      S.circuits = h.passes;
      S.angle = hl.angle;
      S.pitch = hl.pitch;
      S.coverage = hl.coverage;
      S.turnaround_slippage = hl.reversal_slippage;
      for_pass_points(out.circuits, [&](const FibrePoint& p) {
        S.max_slippage = std::max(S.max_slippage, p.slippage);
      });
      // At the reversals: the largest within half a band of the range ends.
      S.thickness_turnaround = 0.0;
      for (std::size_t i = 0; i < surface.points.size(); ++i) {
        const double x = surface.points[i].x();
        if (std::min(std::abs(x - hl.x0), std::abs(x - hl.x1)) <= 0.5 * S.band_width) {
          S.thickness_turnaround = std::max(S.thickness_turnaround, th.thickness[i]);
        }
      }
      for (const std::string& w : hl.warnings) warnings.push_back(w);
    } else {
      // The winding stages of a one-layer job (planner/pipeline.h) on the current surface.
      PipelineOptions quiet;
      PipelineResult pr;
      WindingOptions wopt = L.winding;
      const double shift = helical_index++ * job.design.turnaround_stagger * wopt.band_width;
      if (shift > 0.0 && R.revolution) {
        double rs = 0.0;
        for (const Vec2& p : surface.points) rs = std::max(rs, p.y());
        if (std::isfinite(wopt.turnaround)) {
          wopt.turnaround += shift;
        } else if (std::isfinite(wopt.angle)) {
          wopt.turnaround = rs * std::sin(wopt.angle * M_PI / 180.0) + shift;
          wopt.angle = std::nan("");
        } else {
          wopt.turnaround = opening + 0.5 * wopt.band_width + shift;
        }
        if (!(wopt.turnaround < rs)) {
          throw InputError(what + ": design.turnaround_stagger moves the turnaround to r = " +
                           format_number("%.4g", wopt.turnaround) +
                           " mm, beyond the largest radius of the surface (" +
                           format_number("%.4g", rs) + " mm)");
        }
      }
      if (k == 0) {
        pr = plan_winding(md, job, wopt, quiet);
      } else if (R.revolution) {
        pr = plan_winding(built_mandrel(md, *under, true, forward_profile(surface)), job, wopt,
                          quiet);
        out.surface = under;
      } else {
        pr = plan_winding(built_mandrel(md, built.mesh, false, md.profile), job, wopt, quiet);
        out.surface = under;
      }
      struct {
        std::vector<Circuit> circuits;
        PlanMetrics metrics;
      } hl{std::move(pr.plan.circuits), std::move(pr.plan.metrics)};
      out.circuits = std::move(hl.circuits);
      if (k > 0) {
        for (Circuit& c : out.circuits) {
          for (FibrePoint& p : c.points) p.face = -1;
        }
      }
      std::vector<double> cs, angles;
      const double xm = 0.5 * (cylinder.first + cylinder.second);
      const double band = (cylinder.second - cylinder.first) / 6.0;
      for_pass_points(out.circuits, [&](const FibrePoint& p) {
        const double a = p.winding_angle * M_PI / 180.0;
        cs.push_back(axis.radius(p.position) * std::sin(a));
        if (!R.revolution || std::abs(axis.axial(p.position) - xm) <= band) {
          angles.push_back(p.winding_angle);
        }
      });
      // The Clairaut route's turnaround parallel, else the median measured on the passes.
      S.clairaut =
          hl.metrics.pattern_info.geodesic ? hl.metrics.pattern_info.turnaround_radius : median(cs);
      S.angle = median(angles);
      S.circuits = hl.metrics.circuits;
      S.coverage = hl.metrics.cover_factor;
      S.max_slippage = hl.metrics.max_slippage;
      S.turnaround_slippage = hl.metrics.turnarounds.max_slippage;
      for (const std::string& w : hl.metrics.warnings) warnings.push_back(L.name + ": " + w);
      if (!have_metrics) {
        metrics = hl.metrics;
        have_metrics = true;
      }
      if (R.revolution) {
        th = job.design.dome_thickness == DomeThicknessModel::Spline
                 ? helical_layer_thickness_spline(surface, S.clairaut, S.circuits, S.band_width,
                                                  t_band)
                 : helical_layer_thickness(surface, S.clairaut, S.circuits, S.band_width, t_band);
        double tt = 0.0;
        for (std::size_t i = 0; i < surface.points.size(); ++i) {
          if (std::abs(surface.points[i].y() - S.clairaut) <= S.band_width) {
            tt = std::max(tt, th.thickness[i]);
          }
        }
        S.thickness_turnaround = tt;
      }
    }
    // Material and lengths.
    for (const Circuit& c : out.circuits) {
      if (!c.points.empty()) S.band_length += c.points.back().s - c.points.front().s;
    }
    out.material = estimate_material(job.material, S.band_width, S.band_length);
    S.fibre_length = out.material.fibre_length;
    S.fibre_mass = out.material.fibre_mass;
    S.resin_mass = out.material.resin_mass;
    R.total += out.material;

    // Thickness on the mandrel's faces and the next surface.
    if (R.revolution) {
      S.surface_radius = 0.0;
      for (const Vec2& p : surface.points) S.surface_radius = std::max(S.surface_radius, p.y());
      S.thickness_cylinder =
          th.thickness[nearest_axial(surface, 0.5 * (cylinder.first + cylinder.second))];
      S.thickness_max = th.max();
      LayerThickness on_mandrel;
      on_mandrel.s = R.profiles.mandrel.s;
      on_mandrel.thickness = th.thickness;
      out.face_thickness.resize(ws.mesh.num_faces());
      for (int f = 0; f < ws.mesh.num_faces(); ++f) {
        const Vec3 c = ws.mesh.face_centroid(f);
        out.face_thickness[f] =
            on_mandrel.at(R.profiles.mandrel.project(Vec2(axis.axial(c), axis.radius(c))));
      }
      MeridianPolyline next = offset_meridian(surface, th, what);
      R.profiles.names.push_back(L.name);
      R.profiles.thickness.push_back(th);
      if (job.design.dome_thickness == DomeThicknessModel::Spline) {
        R.profiles.alternative_name = "continuity";
        R.profiles.alternative.push_back(
            L.kind == LayerKind::Helical
                ? helical_layer_thickness(surface, S.clairaut, S.circuits, S.band_width, t_band)
                : th);
      }
      R.profiles.surfaces.push_back(next);
      surface = std::move(next);
    } else {
      const Mesh& cur = k == 0 ? ws.mesh : built.mesh;
      S.surface_radius = 0.0;
      for (const Vec3& p : cur.points())
        S.surface_radius = std::max(S.surface_radius, axis.radius(p));
      // Measured thickness per face, then the vertices moved along their normals.
      std::vector<double> length(cur.num_faces(), 0.0);
      {
        const ClosestPointQuery q(cur);
        for (const Circuit& c : out.circuits) {
          for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
            const Vec3 &a = c.points[i].position, &b = c.points[i + 1].position;
            const int f = q.closest(0.5 * (a + b)).point.element;
            if (f >= 0) length[f] += (b - a).norm();
          }
        }
      }
      out.face_thickness = band_spread_thickness(cur, length, S.band_width, t_band);
      S.thickness_max = *std::max_element(out.face_thickness.begin(), out.face_thickness.end());
      std::vector<double> sum(cur.num_vertices(), 0.0), area(cur.num_vertices(), 0.0);
      for (int f = 0; f < cur.num_faces(); ++f) {
        for (int v : cur.triangle(f)) {
          sum[v] += cur.face_area(f) * out.face_thickness[f];
          area[v] += cur.face_area(f);
        }
      }
      std::vector<Vec3> moved = cur.points();
      for (int v = 0; v < cur.num_vertices(); ++v) {
        if (area[v] > 0.0) moved[v] += sum[v] / area[v] * cur.vertex_normal(v);
      }
      Mesh next = cur;
      next.set_points(std::move(moved));
      built = whole_surface(next, axis);
    }
    R.layers.push_back(std::move(out));
    stage(L.name, t0);
  }

  // The plan for the part.
  WindingPlan& plan = R.plan;
  plan.job_name = job.name;
  plan.axis = axis;
  plan.profile = R.revolution ? envelope_profile(forward_profile(surface), md.profile) : md.profile;
  int index = 0;
  for (LayupLayer& L : R.layers) {
    L.summary.first_circuit = static_cast<int>(plan.circuits.size());
    L.summary.circuit_count = static_cast<int>(L.circuits.size());
    for (Circuit c : L.circuits) {
      c.index = index++;
      plan.circuits.push_back(std::move(c));
    }
    plan.layers.push_back(L.summary);
  }
  // design: the netting burst pressure of the wound laminate, layer by layer (cylinder figures).
  if (job.design.has_pressure() && R.revolution) {
    std::vector<NettingLayer> nl;
    for (const LayupLayer& L : R.layers) {
      nl.push_back({L.summary.name, L.summary.angle, L.summary.thickness_cylinder});
    }
    double rc = 0.0;
    for (const Vec2& p : R.profiles.mandrel.points) rc = std::max(rc, p.y());
    R.netting_radius = rc;
    R.netting = netting_burst(nl, rc, job.design.allowable_stress());
    R.has_netting = true;
  }
  metrics.fibre_length = R.total.band_length;
  metrics.circuits = index;
  metrics.warnings = std::move(warnings);
  for (const std::string& w : md.warnings) metrics.warnings.push_back("mandrel: " + w);
  if (!job.cutlines.empty()) {
    t0 = clock::now();
    plan.cutlines = compute_cutlines(md.winding.mesh, md.axis, job.cutlines);
    stage("cutlines", t0);
  }
  metrics.timings = std::move(timings);
  plan.metrics = std::move(metrics);
  return R;
}

}  // namespace windplan
