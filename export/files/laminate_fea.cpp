#include "export/files/laminate_fea.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/mesh/closest_point.h"

namespace windplan {

namespace {

void check_layers(const Mesh& mesh, const std::vector<LaminateLayerFaces>& layers) {
  const std::size_t nf = static_cast<std::size_t>(mesh.num_faces());
  for (std::size_t k = 0; k < layers.size(); ++k) {
    const LaminateLayerFaces& L = layers[k];
    if (L.thickness.size() != nf || L.angles.angle_plus.size() != nf ||
        L.angles.angle_minus.size() != nf || L.angles.length_plus.size() != nf ||
        L.angles.length_minus.size() != nf) {
      throw InputError("laminate layer " + std::to_string(k) + " (" + L.name +
                       "): its per-face arrays do not match the mesh's " + std::to_string(nf) +
                       " faces");
    }
  }
}

std::string sanitise(const std::string& s) {
  std::string out;
  for (char ch : s) out += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return out;
}

// Shortest round-trip form (%.17g would do; %.10g keeps the files small and deterministic).
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v + 0.0);
  return buf;
}

void data_array(std::ostream& o, const std::string& name, const std::vector<double>& v,
                int components = 1) {
  o << "        <DataArray type=\"Float64\" Name=\"" << name << "\"";
  if (components > 1) o << " NumberOfComponents=\"" << components << "\"";
  o << " format=\"ascii\">\n         ";
  for (std::size_t i = 0; i < v.size(); ++i) o << ' ' << number(v[i]);
  o << "\n        </DataArray>\n";
}

}  // namespace

std::vector<Vec3> face_meridians(const Mesh& mesh, const SpindleAxis& axis) {
  std::vector<Vec3> m(mesh.num_faces(), Vec3::Zero());
  const Vec3 d = axis.direction.normalized();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 n = mesh.face_normal(f);
    const Vec3 p = d - d.dot(n) * n;
    if (p.norm() > 1e-12) m[f] = p.normalized();
  }
  return m;
}

FaceFibreAngles measure_face_angles(const Mesh& mesh, const SpindleAxis& axis,
                                    const std::vector<Circuit>& circuits) {
  if (mesh.num_faces() == 0) throw InputError("laminate: the mesh has no faces");
  const int nf = mesh.num_faces();
  FaceFibreAngles a;
  a.angle_plus.assign(nf, 0.0);
  a.angle_minus.assign(nf, 0.0);
  a.length_plus.assign(nf, 0.0);
  a.length_minus.assign(nf, 0.0);
  const std::vector<Vec3> meridian = face_meridians(mesh, axis);
  const ClosestPointQuery query(mesh);
  // Segments longer than half the mean edge are split, so that each piece falls in one face.
  const double piece = 0.5 * mesh.edge_length_stats()[1];
  for (const Circuit& c : circuits) {
    for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
      const Vec3 &p = c.points[i].position, &q = c.points[i + 1].position;
      const double len = (q - p).norm();
      if (!(len > 0.0)) continue;
      const int pieces = piece > 0.0 ? std::max(1, static_cast<int>(std::ceil(len / piece))) : 1;
      for (int k = 0; k < pieces; ++k) {
        const int f = query.closest(p + (k + 0.5) / pieces * (q - p)).point.element;
        if (f < 0) continue;
        const Vec3 n = mesh.face_normal(f), &m = meridian[f];
        if (m.isZero()) continue;  // a face normal to the axis has no meridian
        const Vec3 h = m.cross(n);
        Vec3 t = (q - p) / len;
        if (t.dot(m) < 0.0) t = -t;
        const double angle = std::atan2(t.dot(h), t.dot(m)) * 180.0 / M_PI;
        const double l = len / pieces;
        if (angle > 0.0) {
          a.angle_plus[f] += angle * l;
          a.length_plus[f] += l;
        } else {
          a.angle_minus[f] += angle * l;
          a.length_minus[f] += l;
        }
      }
    }
  }
  for (int f = 0; f < nf; ++f) {
    if (a.length_plus[f] > 0.0) a.angle_plus[f] /= a.length_plus[f];
    if (a.length_minus[f] > 0.0) a.angle_minus[f] /= a.length_minus[f];
  }
  return a;
}

CsvTable laminate_table(const Mesh& mesh, const std::vector<LaminateLayerFaces>& layers) {
  check_layers(mesh, layers);
  CsvTable t;
  t.header = {"face",
              "layer",
              "thickness [mm]",
              "angle_plus [deg]",
              "angle_minus [deg]",
              "length_plus [mm]",
              "length_minus [mm]",
              "cx [mm]",
              "cy [mm]",
              "cz [mm]"};
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 c = mesh.face_centroid(f);
    for (std::size_t k = 0; k < layers.size(); ++k) {
      const LaminateLayerFaces& L = layers[k];
      t.rows.push_back({static_cast<double>(f), static_cast<double>(k), L.thickness[f],
                        L.angles.angle_plus[f], L.angles.angle_minus[f], L.angles.length_plus[f],
                        L.angles.length_minus[f], c.x(), c.y(), c.z()});
    }
  }
  return t;
}

std::string laminate_vtu(const Mesh& mesh, const SpindleAxis& axis,
                         const std::vector<LaminateLayerFaces>& layers) {
  check_layers(mesh, layers);
  const int nf = mesh.num_faces();
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n"
    << "  <UnstructuredGrid>\n"
    << "    <Piece NumberOfPoints=\"" << mesh.num_vertices() << "\" NumberOfCells=\"" << nf
    << "\">\n"
    << "      <Points>\n";
  std::vector<double> xyz;
  for (const Vec3& p : mesh.points()) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  data_array(o, "Points", xyz, 3);
  o << "      </Points>\n      <Cells>\n"
    << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n         ";
  for (int f = 0; f < nf; ++f) {
    for (int v : mesh.triangle(f)) o << ' ' << v;
  }
  o << "\n        </DataArray>\n"
    << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
  for (int f = 0; f < nf; ++f) o << ' ' << 3 * (f + 1);
  o << "\n        </DataArray>\n"
    << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n         ";
  for (int f = 0; f < nf; ++f) o << " 5";  // VTK_TRIANGLE
  o << "\n        </DataArray>\n      </Cells>\n"
    << "      <CellData Scalars=\"total_thickness_mm\">\n";
  std::vector<double> total(nf, 0.0), mer;
  for (const LaminateLayerFaces& L : layers) {
    for (int f = 0; f < nf; ++f) total[f] += L.thickness[f];
  }
  data_array(o, "total_thickness_mm", total);
  for (const Vec3& m : face_meridians(mesh, axis)) mer.insert(mer.end(), {m.x(), m.y(), m.z()});
  data_array(o, "meridian", mer, 3);
  for (std::size_t k = 0; k < layers.size(); ++k) {
    const LaminateLayerFaces& L = layers[k];
    const std::string p = "L" + std::to_string(k + 1) + "_" + sanitise(L.name) + "_";
    data_array(o, p + "thickness_mm", L.thickness);
    data_array(o, p + "angle_plus_deg", L.angles.angle_plus);
    data_array(o, p + "angle_minus_deg", L.angles.angle_minus);
    data_array(o, p + "length_plus_mm", L.angles.length_plus);
    data_array(o, p + "length_minus_mm", L.angles.length_minus);
  }
  o << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return o.str();
}

std::vector<std::string> write_laminate_fea(const std::filesystem::path& dir, const Mesh& mesh,
                                            const SpindleAxis& axis,
                                            const std::vector<LaminateLayerFaces>& layers) {
  write_csv_file(dir / "laminate.csv", laminate_table(mesh, layers));
  write_text_atomically(dir / "laminate.vtu", laminate_vtu(mesh, axis, layers));
  return {"laminate.csv", "laminate.vtu"};
}

}  // namespace windplan
