#include "geometry/region/centre_line_region.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/region/plane_cut.h"
#include "geometry/region/plane_section.h"

namespace windplan {

namespace {

std::string mm(double v) { return format_fixed(v, 2) + " mm"; }

// One end: the plane normal to the centre line at station s and its section loop's radius.
struct EndPlane {
  Vec3 centre, normal;
  double radius = 0.0;  // mm, the largest distance of the section loop's points from `centre`
};

EndPlane end_plane(const Mesh& full, const Spine& spine, double s, const std::string& key) {
  EndPlane e;
  e.centre = spine.point(s);
  e.normal = spine.tangent(s);
  const SpindleAxis line{e.centre, e.normal};
  const std::vector<PlaneSection> chains =
      plane_sections(full, e.normal, e.normal.dot(e.centre), line);
  int open = 0, closed = 0;
  const PlaneSection* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  for (const PlaneSection& c : chains) {
    if (!c.closed) {
      ++open;
      continue;
    }
    ++closed;
    if (std::abs(c.winding) != 1) continue;
    const double d = (PlaneSectioner::centroid(c.points) - e.centre).norm();
    if (d < best_d) best_d = d, best = &c;
  }
  if (!best) {
    throw ConfigError(key + ": the plane normal to the centre line at " + mm(s) +
                      " does not cut a closed section of the tube around the centre line (" +
                      std::to_string(closed) + " closed and " + std::to_string(open) +
                      " open section chain(s) there): move the station inside the tube");
  }
  for (const Vec3& p : best->points) e.radius = std::max(e.radius, (p - e.centre).norm());
  return e;
}

}  // namespace

RegionSelection select_centre_line_region(const Mesh& full, const Spine& spine,
                                          const CentreLineEnds& ends, const SpindleAxis& axis,
                                          int component, const PlaneCutOptions& cut_options) {
  if (spine.empty()) throw ConfigError(ends.from_key + ": the tube has no centre line");
  const double L = spine.length();
  const std::string range = "(0 .. " + mm(L) + ", its ends excluded: they are the tube's own)";
  for (const auto& [v, key] : {std::pair{ends.from, ends.from_key}, {ends.to, ends.to_key}}) {
    if (!std::isfinite(v) || !(v > 0.0) || !(v < L)) {
      throw ConfigError(key + ": " + mm(v) + " is outside the tube's centre line " + range);
    }
  }
  if (!(ends.from < ends.to)) {
    throw ConfigError(ends.to_key + ": " + mm(ends.to) + " must lie after " + ends.from_key + " (" +
                      mm(ends.from) + ") along the centre line");
  }
  const EndPlane e0 = end_plane(full, spine, ends.from, ends.from_key);
  const EndPlane e1 = end_plane(full, spine, ends.to, ends.to_key);

  // Exact cuts, one plane after the other; face_parent composed back to `full`.
  PlaneCutResult c0 = cut_at_stations(full, SpindleAxis{e0.centre, e0.normal}, {0.0}, cut_options);
  PlaneCutResult c1 =
      cut_at_stations(c0.mesh, SpindleAxis{e1.centre, e1.normal}, {0.0}, cut_options);
  RegionSelection out;
  out.split_edges = c0.split_edges + c1.split_edges;
  out.split_faces = c0.split_faces + c1.split_faces;
  out.moved_vertices = c0.moved_vertices + c1.moved_vertices;
  out.max_move = std::max(c0.max_move, c1.max_move);
  out.face_parent.resize(c1.face_parent.size());
  for (std::size_t f = 0; f < c1.face_parent.size(); ++f) {
    out.face_parent[f] = c0.face_parent[c1.face_parent[f]];
  }
  out.mesh = std::move(c1.mesh);
  const Mesh& m = out.mesh;
  const double eps = 1e-9 * std::max(1.0, m.bounding_box().diagonal_length());
  std::vector<char> inside(m.num_faces(), 0);
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 q = m.face_centroid(f);
    const double s = spine.project(q);
    const bool after0 = std::abs(s - ends.from) < 2.0 * e0.radius
                            ? e0.normal.dot(q - e0.centre) > eps
                            : s > ends.from;
    const bool before1 =
        std::abs(s - ends.to) < 2.0 * e1.radius ? e1.normal.dot(q - e1.centre) < -eps : s < ends.to;
    inside[f] = after0 && before1;
  }
  out.candidates = candidate_regions(m, inside, axis);
  // An annulus here is one component with two loops and genus 0; its loops are normal sections
  // of the tube, not loops around the spindle axis.
  int largest = -1;
  for (std::size_t i = 0; i < out.candidates.size(); ++i) {
    CandidateRegion& c = out.candidates[i];
    c.annulus = c.loops == 2 && c.genus == 0;
    if (c.annulus && largest < 0) largest = static_cast<int>(i);  // sorted by area
  }
  auto listing = [&]() {
    std::string s;
    for (const CandidateRegion& c : out.candidates) s += (s.empty() ? "" : "; ") + c.brief();
    return s.empty() ? std::string("none") : s;
  };
  const std::string between =
      "between the sections at " + mm(ends.from) + " and " + mm(ends.to) + " along the centre line";
  if (component > 0) {
    if (component > static_cast<int>(out.candidates.size()) ||
        !out.candidates[component - 1].annulus) {
      throw ConfigError("mandrel.region.component: " + std::to_string(component) +
                        " is not an annulus " + between + "; candidates: " + listing());
    }
    out.chosen = component - 1;
  } else {
    if (largest < 0) {
      throw ConfigError("mandrel.region.centre_line: no surface " + between +
                        " is an annulus (one part, two loops, genus 0); candidates: " + listing());
    }
    out.chosen = largest;
  }
  out.keep.assign(m.num_faces(), 0);
  for (int f : out.candidates[out.chosen].face_list) out.keep[f] = 1;
  return out;
}

}  // namespace windplan
