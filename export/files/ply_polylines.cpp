#include "export/files/ply_polylines.h"

#include <charconv>
#include <string>

namespace windplan {

namespace {

// A coordinate as printf("%.10g") prints it: std::to_chars with a precision prints exactly that,
// several times faster (a job's paths hold hundreds of thousands of points). + 0.0: no "-0".
void put_number(std::string& out, double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v + 0.0, std::chars_format::general, 10);
  out.append(buf, r.ptr);
}

void put_integer(std::string& out, long long v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void put_point(std::string& out, const Vec3& p) {
  put_number(out, p.x());
  out += ' ';
  put_number(out, p.y());
  out += ' ';
  put_number(out, p.z());
}

void put_vertex(std::string& out, const Vec3& p, long long circuit) {
  put_point(out, p);
  out += ' ';
  put_integer(out, circuit);
  out += '\n';
}

void put_edge(std::string& out, std::size_t a, std::size_t b, long long circuit) {
  put_integer(out, static_cast<long long>(a));
  out += ' ';
  put_integer(out, static_cast<long long>(b));
  out += ' ';
  put_integer(out, circuit);
  out += '\n';
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
  std::string out =
      "ply\nformat ascii 1.0\n"
      "comment windplan paths: circuits (circuit >= 0), cut-line k has circuit = -1 - k\n"
      "comment units mm\n"
      "element vertex " +
      std::to_string(nv) +
      "\n"
      "property double x\nproperty double y\nproperty double z\nproperty int circuit\n"
      "element edge " +
      std::to_string(ne) +
      "\n"
      "property int vertex1\nproperty int vertex2\nproperty int circuit\nend_header\n";
  out.reserve(out.size() + 48 * nv + 20 * ne);
  for (const Circuit& c : plan.circuits) {
    for (const FibrePoint& p : c.points) put_vertex(out, p.position, c.index);
  }
  for (std::size_t k = 0; k < plan.cutlines.size(); ++k) {
    for (const Vec3& p : plan.cutlines[k].points) put_vertex(out, p, -1 - static_cast<long long>(k));
  }
  std::size_t base = 0;
  for (const Circuit& c : plan.circuits) {
    for (std::size_t i = 1; i < c.points.size(); ++i) put_edge(out, base + i - 1, base + i, c.index);
    base += c.points.size();
  }
  for (std::size_t k = 0; k < plan.cutlines.size(); ++k) {
    const CutLine& l = plan.cutlines[k];
    const long long id = -1 - static_cast<long long>(k);
    for (std::size_t i = 1; i < l.points.size(); ++i) put_edge(out, base + i - 1, base + i, id);
    if (l.closed && l.points.size() > 2) {
      put_edge(out, base + l.points.size() - 1, base, id);
    }
    base += l.points.size();
  }
  return out;
}

}  // namespace windplan
