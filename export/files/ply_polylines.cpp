#include "export/files/ply_polylines.h"

#include <cstdio>
#include <sstream>

namespace windplan {

namespace {

void put_point(std::ostringstream& out, const Vec3& p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.10g %.10g %.10g", p.x() + 0.0, p.y() + 0.0, p.z() + 0.0);
  out << buf;
}

}  // namespace

std::string paths_ply(const WindingPlan& plan) {
  std::size_t nv = 0, ne = 0;
  for (const Circuit& c : plan.circuits) {
    nv += c.points.size();
    if (c.points.size() > 1) ne += c.points.size() - 1;
  }
  for (const CutLine& l : plan.cutlines) {
    nv += l.points.size();
    if (l.points.size() > 1) ne += l.points.size() - 1 + (l.closed && l.points.size() > 2);
  }
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\n"
         "comment windplan paths: circuits (circuit >= 0), cut-line k has circuit = -1 - k\n"
         "comment units mm\n"
      << "element vertex " << nv << "\n"
      << "property double x\nproperty double y\nproperty double z\nproperty int circuit\n"
      << "element edge " << ne << "\n"
      << "property int vertex1\nproperty int vertex2\nproperty int circuit\nend_header\n";
  for (const Circuit& c : plan.circuits) {
    for (const FibrePoint& p : c.points) {
      put_point(out, p.position);
      out << " " << c.index << "\n";
    }
  }
  for (std::size_t k = 0; k < plan.cutlines.size(); ++k) {
    for (const Vec3& p : plan.cutlines[k].points) {
      put_point(out, p);
      out << " " << -1 - static_cast<long>(k) << "\n";
    }
  }
  std::size_t base = 0;
  for (const Circuit& c : plan.circuits) {
    for (std::size_t i = 1; i < c.points.size(); ++i) {
      out << base + i - 1 << " " << base + i << " " << c.index << "\n";
    }
    base += c.points.size();
  }
  for (std::size_t k = 0; k < plan.cutlines.size(); ++k) {
    const CutLine& l = plan.cutlines[k];
    const long id = -1 - static_cast<long>(k);
    for (std::size_t i = 1; i < l.points.size(); ++i) {
      out << base + i - 1 << " " << base + i << " " << id << "\n";
    }
    if (l.closed && l.points.size() > 2) {
      out << base + l.points.size() - 1 << " " << base << " " << id << "\n";
    }
    base += l.points.size();
  }
  return out.str();
}

}  // namespace windplan
