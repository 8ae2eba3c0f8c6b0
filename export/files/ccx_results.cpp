#include "export/files/ccx_results.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

bool numbers(const std::string& line, std::vector<double>* out) {
  std::istringstream in(line);
  out->clear();
  std::string tok;
  while (in >> tok) {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0') {
      // A trailing orientation name is allowed after the numbers.
      return !out->empty() && std::isalpha(static_cast<unsigned char>(tok[0]));
    }
    out->push_back(v);
  }
  return !out->empty();
}

}  // namespace

CcxResults read_ccx_dat(const std::filesystem::path& dat) {
  std::ifstream in(dat);
  if (!in) throw IoError("cannot read " + dat.string());
  CcxResults r;
  enum { None, Disp, Stress, Strain } mode = None;
  std::string line;
  std::vector<double> v;
  while (std::getline(in, line)) {
    if (line.find("displacements") != std::string::npos) {
      mode = Disp;
      continue;
    }
    if (line.find("stresses") != std::string::npos) {
      mode = Stress;
      continue;
    }
    if (line.find("strains") != std::string::npos) {
      mode = Strain;
      continue;
    }
    if (line.find("for set") != std::string::npos) {
      mode = None;
      continue;
    }
    if (mode == None || !numbers(line, &v)) continue;
    if (mode == Disp && v.size() >= 4) {
      r.displacement[static_cast<int>(v[0])] = Vec3(v[1], v[2], v[3]);
    } else if ((mode == Stress || mode == Strain) && v.size() >= 8) {
      CcxResults::IpValues q;
      q.element = static_cast<int>(v[0]);
      q.ip = static_cast<int>(v[1]);
      for (int i = 0; i < 6; ++i) q.v[i] = v[2 + i];
      (mode == Stress ? r.stress : r.strain).push_back(q);
    }
  }
  if (r.displacement.empty() && r.strain.empty()) {
    throw InputError(dat.string() + ": no displacements or strains (did ccx finish?)");
  }
  return r;
}

PlyAllowables ply_allowables(const ElasticConstants& c, double x, double y, double s) {
  return {x / c.e1, y / c.e2, s / c.g12};
}

FeaCheck check_plies(const CcxResults& res, const CsvTable& plies,
                     const std::vector<std::string>& names, const PlyAllowables& al,
                     const std::set<int>& skip) {
  // Per element: its plies (layer, thickness) in order.
  std::map<int, std::vector<std::pair<int, double>>> layout;
  for (const std::vector<double>& row : plies.rows) {
    if (row.size() < 5) throw InputError("model_plies.csv: a row has fewer than 5 values");
    layout[static_cast<int>(row[0])].push_back({static_cast<int>(row[2]), row[4]});
  }
  std::map<int, std::vector<const CcxResults::IpValues*>> strain, stress;
  for (const auto& q : res.strain) strain[q.element].push_back(&q);
  for (const auto& q : res.stress) stress[q.element].push_back(&q);
  FeaCheck out;
  out.layers.resize(names.size());
  std::vector<double> wsum(names.size(), 0.0), tsum(names.size(), 0.0);
  std::vector<bool> seen(names.size(), false);
  for (std::size_t k = 0; k < names.size(); ++k) out.layers[k].name = names[k];
  for (const auto& [e, ply] : layout) {
    if (skip.count(e)) continue;
    const auto it = strain.find(e);
    if (it == strain.end()) {
      throw InputError("element " + std::to_string(e) + " has no strains in the results");
    }
    const std::vector<const CcxResults::IpValues*>& ips = it->second;
    const std::vector<const CcxResults::IpValues*>* sp = stress.count(e) ? &stress.at(e) : nullptr;
    if (ips.size() % ply.size() != 0) {
      throw InputError("element " + std::to_string(e) + ": " + std::to_string(ips.size()) +
                       " integration points do not split over " + std::to_string(ply.size()) +
                       " plies");
    }
    const std::size_t per = ips.size() / ply.size();
    ++out.elements;
    for (std::size_t p = 0; p < ply.size(); ++p) {
      double e1 = 0.0, e2 = 0.0, g12 = 0.0, s1 = 0.0;
      for (std::size_t i = p * per; i < (p + 1) * per; ++i) {
        e1 += ips[i]->v[0];
        e2 += ips[i]->v[1];
        g12 += 2.0 * ips[i]->v[3];
        if (sp && i < sp->size()) s1 += (*sp)[i]->v[0];
      }
      e1 /= per;
      e2 /= per;
      g12 /= per;
      s1 /= per;
      const int k = ply[p].first;
      if (k < 0 || k >= static_cast<int>(names.size())) continue;
      FeaLayerCheck& L = out.layers[k];
      if (!seen[k]) {
        L.fibre_strain_max = L.fibre_strain_min = e1;
        L.fibre_stress_max = L.fibre_stress_min = s1;
        seen[k] = true;
      }
      L.fibre_strain_max = std::max(L.fibre_strain_max, e1);
      L.fibre_strain_min = std::min(L.fibre_strain_min, e1);
      L.fibre_stress_max = std::max(L.fibre_stress_max, s1);
      L.fibre_stress_min = std::min(L.fibre_stress_min, s1);
      wsum[k] += e1 * ply[p].second;
      tsum[k] += ply[p].second;
      const double f1 = std::abs(e1) / al.fibre_strain, f2 = std::abs(e2) / al.transverse_strain,
                   f6 = std::abs(g12) / al.shear_strain;
      const double f = std::max({f1, f2, f6});
      L.fibre_factor = std::max(L.fibre_factor, f1);
      if (f > L.failure_factor) {
        L.failure_factor = f;
        L.element = e;
        L.mode = f == f1 ? "fibre" : (f == f2 ? "transverse" : "shear");
      }
    }
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    FeaLayerCheck& L = out.layers[k];
    if (tsum[k] > 0.0) L.fibre_strain_mean = wsum[k] / tsum[k];
    out.fibre_factor = std::max(out.fibre_factor, L.fibre_factor);
    if (L.failure_factor > out.failure_factor) {
      out.failure_factor = L.failure_factor;
      out.governing = L.name + ": " + L.mode;
    }
  }
  return out;
}

InpMesh read_inp_mesh(const std::filesystem::path& inp) {
  std::ifstream in(inp);
  if (!in) throw IoError("cannot read " + inp.string());
  InpMesh m;
  enum { None, Node, Element } mode = None;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.rfind("**", 0) == 0) continue;
    if (line.rfind("*", 0) == 0) {
      mode = line.rfind("*NODE,", 0) == 0 || line == "*NODE" ? Node
             : line.rfind("*ELEMENT", 0) == 0                ? Element
                                                             : None;
      continue;
    }
    if (mode == None) continue;
    std::vector<double> v;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      char* end = nullptr;
      v.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str()) {
        throw InputError(inp.string() + ":" + std::to_string(n) + ": '" + cell +
                         "' is not a number");
      }
    }
    if (mode == Node && v.size() >= 4) {
      m.nodes[static_cast<int>(v[0])] = Vec3(v[1], v[2], v[3]);
    } else if (mode == Element && v.size() >= 4) {
      std::vector<int> e;
      for (std::size_t i = 1; i < v.size(); ++i) e.push_back(static_cast<int>(v[i]));
      m.elements[static_cast<int>(v[0])] = e;
    }
  }
  return m;
}

std::set<int> elements_near_free_edges(const InpMesh& m, double distance) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& [id, e] : m.elements) {
    for (int i = 0; i < 3; ++i) {
      const int a = e[i], b = e[(i + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<Vec3> edge_nodes;
  for (const auto& [key, count] : uses) {
    if (count != 1) continue;
    edge_nodes.push_back(m.nodes.at(key.first));
    edge_nodes.push_back(m.nodes.at(key.second));
  }
  std::set<int> out;
  for (const auto& [id, e] : m.elements) {
    const Vec3 c = (m.nodes.at(e[0]) + m.nodes.at(e[1]) + m.nodes.at(e[2])) / 3.0;
    for (const Vec3& p : edge_nodes) {
      if ((p - c).norm() < distance) {
        out.insert(id);
        break;
      }
    }
  }
  return out;
}

std::map<int, Vec3d> element_membrane_strains(const CcxResults& res, const CsvTable& plies) {
  std::map<int, std::vector<std::pair<double, double>>> layout;  // (angle, thickness)
  for (const std::vector<double>& row : plies.rows) {
    if (row.size() < 5) throw InputError("model_plies.csv: a row has fewer than 5 values");
    layout[static_cast<int>(row[0])].push_back({row[3], row[4]});
  }
  std::map<int, std::vector<const CcxResults::IpValues*>> strain;
  for (const auto& q : res.strain) strain[q.element].push_back(&q);
  std::map<int, Vec3d> out;
  for (const auto& [e, ply] : layout) {
    const auto it = strain.find(e);
    if (it == strain.end() || it->second.size() % ply.size() != 0) {
      throw InputError("element " + std::to_string(e) +
                       ": its integration points do not match its plies");
    }
    const std::size_t per = it->second.size() / ply.size();
    Vec3d sum{0.0, 0.0, 0.0};
    double t = 0.0;
    for (std::size_t p = 0; p < ply.size(); ++p) {
      double e1 = 0.0, e2 = 0.0, g = 0.0;
      for (std::size_t i = p * per; i < (p + 1) * per; ++i) {
        e1 += it->second[i]->v[0] / per;
        e2 += it->second[i]->v[1] / per;
        g -= 2.0 * it->second[i]->v[3] / per;  // local 2 = n x f = -(-s m + c h)
      }
      const double a = ply[p].first * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
      const double w = ply[p].second;
      sum[0] += w * (e1 * c * c + e2 * s * s - g * s * c);
      sum[1] += w * (e1 * s * s + e2 * c * c + g * s * c);
      sum[2] += w * (2.0 * (e1 - e2) * s * c + g * (c * c - s * s));
      t += w;
    }
    out[e] = {sum[0] / t, sum[1] / t, sum[2] / t};
  }
  return out;
}

CsvTable read_numeric_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw IoError("cannot read " + file.string());
  CsvTable t;
  std::string line;
  if (!std::getline(in, line)) throw InputError(file.string() + ": empty");
  std::stringstream h(line);
  std::string cell;
  while (std::getline(h, cell, ',')) t.header.push_back(cell);
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream s(line);
    while (std::getline(s, cell, ',')) {
      char* end = nullptr;
      row.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str()) {
        throw InputError(file.string() + ":" + std::to_string(n) + ": '" + cell +
                         "' is not a number");
      }
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace windplan
