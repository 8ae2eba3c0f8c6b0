#include "export/files/fea_deck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v + 0.0);
  return buf;
}

Vec3 radial_part(const SpindleAxis& axis, const Vec3& p) {
  const Vec3 d = p - axis.origin;
  return d - d.dot(axis.direction) * axis.direction;
}

}  // namespace

bool FeaModelOptions::is_valid(std::string* why) const {
  if (!(pressure > 0.0) || !std::isfinite(pressure)) {
    if (why) *why = "pressure must be > 0 MPa (got " + format_number("%g", pressure) + ")";
    return false;
  }
  if (!(min_thickness > 0.0)) {
    if (why) *why = "min_thickness must be > 0 mm";
    return false;
  }
  return true;
}

FeaModel build_fea_model(const Mesh& mesh, const SpindleAxis& axis_in,
                         const std::vector<LaminateLayerFaces>& layers,
                         const std::vector<FeaLayerFallback>& fallback,
                         const FeaModelOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("fea: " + why);
  SpindleAxis axis = axis_in;
  axis.direction.normalize();
  const int nf = mesh.num_faces();
  if (fallback.size() != layers.size()) throw InputError("fea: one fallback per layer needed");
  for (const LaminateLayerFaces& L : layers) {
    if (static_cast<int>(L.thickness.size()) != nf ||
        static_cast<int>(L.angles.angle_plus.size()) != nf) {
      throw InputError("fea: layer " + L.name + " does not match the mesh's faces");
    }
  }
  const std::vector<Vec3> meridian = face_meridians(mesh, axis);
  FeaModel M;
  M.pressure = options.pressure;
  for (const LaminateLayerFaces& L : layers) M.layer_names.push_back(L.name);

  std::vector<int> corner(mesh.num_vertices(), -1);
  std::map<std::pair<int, int>, int> midside;
  auto corner_node = [&](int v) {
    if (corner[v] < 0) {
      corner[v] = static_cast<int>(M.nodes.size());
      M.nodes.push_back(mesh.position(v));
    }
    return corner[v];
  };
  std::vector<std::array<int, 3>> tri_nodes;
  for (int f = 0; f < nf; ++f) {
    double total = 0.0;
    for (const LaminateLayerFaces& L : layers) total += L.thickness[f];
    if (!(total >= options.min_thickness) || meridian[f].norm() == 0.0) {
      ++M.faces_left_out;
      continue;
    }
    std::array<int, 3> v = mesh.triangle(f);
    Vec3 n = mesh.face_normal(f);
    const Vec3 c = mesh.face_centroid(f);
    if (n.dot(radial_part(axis, c)) < 0.0) {  // normal away from the axis
      std::swap(v[1], v[2]);
      n = -n;
    }
    const Vec3 m = meridian[f];
    const Vec3 h = m.cross(n);
    const double r = axis.radius(c);
    std::vector<FeaPly> plies;
    for (std::size_t k = 0; k < layers.size(); ++k) {
      const LaminateLayerFaces& L = layers[k];
      const double t = L.thickness[f];
      if (!(t > 0.0)) continue;
      double ap = L.angles.angle_plus[f], am = L.angles.angle_minus[f];
      const bool hp = L.angles.length_plus[f] > 0.0, hm = L.angles.length_minus[f] > 0.0;
      if (hp && !hm) am = -ap;
      if (hm && !hp) ap = -am;
      if (!hp && !hm) {
        ap = fallback[k].clairaut > 0.0
                 ? std::asin(std::min(1.0, fallback[k].clairaut / std::max(r, 1e-9))) * 180.0 / M_PI
                 : std::abs(fallback[k].angle);
        am = -ap;
      }
      for (double a : {ap, am}) {
        FeaPly p;
        p.layer = static_cast<int>(k);
        p.angle_deg = a;
        p.thickness = 0.5 * t;
        const double ar = a * M_PI / 180.0;
        p.fibre = (std::cos(ar) * m + std::sin(ar) * h).normalized();
        p.across = n.cross(p.fibre).normalized();
        plies.push_back(p);
      }
    }
    std::array<int, 6> e{};
    for (int i = 0; i < 3; ++i) e[i] = corner_node(v[i]);
    tri_nodes.push_back({v[0], v[1], v[2]});
    M.elements.push_back(e);
    M.element_face.push_back(f);
    M.plies.push_back(std::move(plies));
  }
  if (M.elements.empty()) throw InputError("fea: no face of the mesh has laminate");
  // Midside nodes, and the boundary edges (used by one element).
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : tri_nodes) {
    for (int i = 0; i < 3; ++i)
      ++uses[{std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3])}];
  }
  for (std::size_t k = 0; k < tri_nodes.size(); ++k) {
    const auto& t = tri_nodes[k];
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      auto it = midside.find(key);
      if (it == midside.end()) {
        Vec3 p = 0.5 * (mesh.position(a) + mesh.position(b));
        if (options.revolution) {
          const Vec3 rp = radial_part(axis, p);
          const double want = 0.5 * (axis.radius(mesh.position(a)) + axis.radius(mesh.position(b)));
          if (rp.norm() > 1e-12) p += (want / rp.norm() - 1.0) * rp;
        }
        it = midside.emplace(key, static_cast<int>(M.nodes.size())).first;
        M.nodes.push_back(p);
      }
      M.elements[k][3 + i] = it->second;
    }
  }
  // End loads: per side of the middle of the axial extent, p times the enclosed area.
  double lo = 1e300, hi = -1e300;
  for (const Vec3& p : M.nodes) {
    lo = std::min(lo, axis.axial(p));
    hi = std::max(hi, axis.axial(p));
  }
  const double mid = 0.5 * (lo + hi);
  struct Edge {
    int a, b, m;  // model nodes
  };
  std::vector<Edge> side[2];
  double area[2] = {0.0, 0.0}, length[2] = {0.0, 0.0};
  for (std::size_t k = 0; k < tri_nodes.size(); ++k) {
    const auto& t = tri_nodes[k];
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      if (uses[{std::min(a, b), std::max(a, b)}] != 1) continue;
      const Vec3 pa = mesh.position(a), pb = mesh.position(b);
      const int s = 0.5 * (axis.axial(pa) + axis.axial(pb)) < mid ? 0 : 1;
      side[s].push_back({corner[a], corner[b], M.elements[k][3 + i]});
      area[s] += 0.5 * radial_part(axis, pa).cross(radial_part(axis, pb)).dot(axis.direction);
      length[s] += (pb - pa).norm();
    }
  }
  for (int s = 0; s < 2; ++s) {
    if (side[s].empty()) continue;
    const double force = options.pressure * std::abs(area[s]);
    M.end_force[s] = force;
    const Vec3 dir = (s == 0 ? -1.0 : 1.0) * axis.direction;
    std::map<int, Vec3> acc;
    for (const Edge& e : side[s]) {
      const double q = force / length[s] * (M.nodes[e.b] - M.nodes[e.a]).norm();
      for (int node : {e.a, e.b})
        acc.try_emplace(node, Vec3::Zero()).first->second += q / 6.0 * dir;
      acc.try_emplace(e.m, Vec3::Zero()).first->second += 4.0 * q / 6.0 * dir;
    }
    for (const auto& [node, f] : acc) M.end_loads.push_back({node, f});
  }
  // Supports: 3-2-1 on corner nodes of the middle parallel.
  const Vec3 d = axis.direction;
  const Vec3 e1 = (std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(d).normalized();
  const Vec3 e2 = d.cross(e1);
  double rmax = 0.0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (corner[v] >= 0 && std::abs(axis.axial(mesh.position(v)) - mid) < 0.25 * (hi - lo)) {
      rmax = std::max(rmax, axis.radius(mesh.position(v)));
    }
  }
  auto nearest = [&](const Vec3& target) {
    int best = -1;
    double bd = 1e300;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      if (corner[v] < 0) continue;
      const double dd = (mesh.position(v) - target).squaredNorm();
      if (dd < bd) {
        bd = dd;
        best = corner[v];
      }
    }
    return best;
  };
  const Vec3 centre = axis.origin + mid * d;
  const int A = nearest(centre + rmax * e1), B = nearest(centre - rmax * e1),
            C = nearest(centre + rmax * e2);
  for (const Vec3& u : {e1, e2, d}) M.supports.push_back({A, u});
  M.supports.push_back({B, e2});
  M.supports.push_back({B, d});
  M.supports.push_back({C, d});
  return M;
}

std::string calculix_deck(const FeaModel& M, const ElasticConstants& c,
                          const std::string& heading) {
  std::ostringstream o;
  o << "*HEADING\n" << heading << "\n";
  o << "** windplan structural model (export/files/fea_deck.h): layered S6 shells on the mandrel\n"
    << "** surface, internal pressure " << num(M.pressure) << " MPa, closed-end loads "
    << num(M.end_force[0]) << " N and " << num(M.end_force[1]) << " N. Units: mm, N, MPa.\n";
  for (std::size_t k = 0; k < M.layer_names.size(); ++k) {
    o << "** layer " << k << ": " << M.layer_names[k] << "\n";
  }
  o << "*NODE, NSET=NALL\n";
  for (std::size_t i = 0; i < M.nodes.size(); ++i) {
    const Vec3& p = M.nodes[i];
    o << i + 1 << ", " << num(p.x()) << ", " << num(p.y()) << ", " << num(p.z()) << "\n";
  }
  o << "*ELEMENT, TYPE=S6, ELSET=EALL\n";
  for (std::size_t e = 0; e < M.elements.size(); ++e) {
    o << e + 1;
    for (int n : M.elements[e]) o << ", " << n + 1;
    o << "\n";
  }
  o << "*MATERIAL, NAME=PLY\n*ELASTIC, TYPE=ENGINEERING CONSTANTS\n"
    << num(c.e1) << ", " << num(c.e2) << ", " << num(c.e3) << ", " << num(c.nu12) << ", "
    << num(c.nu13) << ", " << num(c.nu23) << ", " << num(c.g12) << ", " << num(c.g13) << "\n"
    << num(c.g23) << "\n";
  for (std::size_t e = 0; e < M.elements.size(); ++e) {
    const std::vector<FeaPly>& plies = M.plies[e];
    for (std::size_t p = 0; p < plies.size(); ++p) {
      const Vec3 &a = plies[p].fibre, &b = plies[p].across;
      o << "*ORIENTATION, NAME=O" << e + 1 << "_" << p + 1 << "\n"
        << num(a.x()) << ", " << num(a.y()) << ", " << num(a.z()) << ", " << num(b.x()) << ", "
        << num(b.y()) << ", " << num(b.z()) << "\n";
    }
    o << "*ELSET, ELSET=E" << e + 1 << "\n" << e + 1 << "\n";
    o << "*SHELL SECTION, ELSET=E" << e + 1 << ", COMPOSITE\n";
    for (std::size_t p = 0; p < plies.size(); ++p) {
      o << num(plies[p].thickness) << ", , PLY, O" << e + 1 << "_" << p + 1 << "\n";
    }
  }
  o << "*BOUNDARY\n";
  std::ostringstream eq;
  for (const FeaModel::Support& s : M.supports) {
    int axis_dof = -1;
    for (int i = 0; i < 3; ++i) {
      if (std::abs(std::abs(s.direction[i]) - 1.0) < 1e-12) axis_dof = i;
    }
    if (axis_dof >= 0) {
      o << s.node + 1 << ", " << axis_dof + 1 << ", " << axis_dof + 1 << "\n";
    } else {
      int terms = 0;
      std::ostringstream t;
      for (int i = 0; i < 3; ++i) {
        if (std::abs(s.direction[i]) > 1e-12) {
          ++terms;
          t << s.node + 1 << ", " << i + 1 << ", " << num(s.direction[i]) << ", ";
        }
      }
      std::string line = t.str();
      line.resize(line.size() - 2);
      eq << "*EQUATION\n" << terms << "\n" << line << "\n";
    }
  }
  o << eq.str();
  o << "*STEP\n*STATIC\n*DLOAD\nEALL, P, " << num(M.pressure) << "\n";
  if (!M.end_loads.empty()) {
    o << "*CLOAD\n";
    for (const FeaModel::Load& l : M.end_loads) {
      for (int i = 0; i < 3; ++i) {
        if (std::abs(l.force[i]) > 0.0) {
          o << l.node + 1 << ", " << i + 1 << ", " << num(l.force[i]) << "\n";
        }
      }
    }
  }
  o << "*NODE PRINT, NSET=NALL\nU\n*EL PRINT, ELSET=EALL\nS, E\n*END STEP\n";
  return o.str();
}

CsvTable fea_plies_table(const FeaModel& M) {
  CsvTable t;
  t.header = {"element", "ply", "layer", "angle [deg]", "thickness [mm]"};
  for (std::size_t e = 0; e < M.plies.size(); ++e) {
    for (std::size_t p = 0; p < M.plies[e].size(); ++p) {
      const FeaPly& q = M.plies[e][p];
      t.rows.push_back({static_cast<double>(e + 1), static_cast<double>(p + 1),
                        static_cast<double>(q.layer), q.angle_deg, q.thickness});
    }
  }
  return t;
}

std::vector<std::string> write_fea_model(const std::filesystem::path& dir, const FeaModel& model,
                                         const ElasticConstants& ply, const std::string& heading) {
  write_text_atomically(dir / "model.inp", calculix_deck(model, ply, heading));
  write_csv_file(dir / "model_plies.csv", fea_plies_table(model));
  return {"model.inp", "model_plies.csv"};
}

}  // namespace windplan
