#include "planner/winding/harmonic.h"

#include <chrono>
#include <cmath>
#include <queue>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

// cot of the angle opposite to interior halfedge h (at the third corner of its face).
double cot_opposite(const Mesh& m, int h) {
  const Vec3& o = m.position(m.opposite_vertex(h));
  const Vec3 a = m.position(m.from(h)) - o, b = m.position(m.to(h)) - o;
  const double s = a.cross(b).norm();
  if (!(s > 0.0)) return 0.0;  // degenerate face: no coupling through it
  return a.dot(b) / s;
}

// Cotangent weight per edge.
std::vector<double> cotan_weights(const Mesh& m) {
  std::vector<double> w(m.num_edges(), 0.0);
  for (int h = 0; h < m.num_interior_halfedges(); ++h) w[m.edge(h)] += 0.5 * cot_opposite(m, h);
  return w;
}

}  // namespace

void check_annulus(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops) {
  int comps = 0;
  annulus.face_components(&comps);
  const int nloops = static_cast<int>(annulus.boundary_loops().size());
  const int genus = annulus.genus();
  if (annulus.num_faces() == 0 || comps != 1 || nloops != 2 || genus != 0) {
    throw TopologyError("the winding surface is not an annulus: it has " + std::to_string(comps) +
                        " component(s), " + std::to_string(nloops) +
                        " boundary loop(s) and genus " + std::to_string(genus) +
                        " (need 1 component, 2 loops, genus 0)");
  }
  for (int i = 0; i < 2; ++i) {
    if (loops[i].empty()) throw InputError("boundary loop " + std::to_string(i) + " is empty");
    for (int v : loops[i]) {
      if (v < 0 || v >= annulus.num_vertices() || !annulus.is_boundary_vertex(v)) {
        throw InputError("boundary loop " + std::to_string(i) + " names vertex " +
                         std::to_string(v) + ", which is not a boundary vertex of the annulus");
      }
    }
  }
}

HarmonicCoordinates compute_harmonic_coordinates(const Mesh& m,
                                                 const std::array<std::vector<int>, 2>& loops) {
  const auto t0 = std::chrono::steady_clock::now();
  check_annulus(m, loops);
  const int nv = m.num_vertices(), nf = m.num_faces();
  const std::vector<double> w = cotan_weights(m);

  // Loop label per vertex: -1 interior, 0 or 1.
  std::vector<int> label(nv, -1);
  for (int i = 0; i < 2; ++i) {
    for (int v : loops[i]) {
      if (label[v] >= 0 && label[v] != i) {
        throw TopologyError("vertex " + std::to_string(v) + " lies on both boundary loops");
      }
      label[v] = i;
    }
  }
  // Any boundary vertex missed by the given loops belongs to the loop of its boundary neighbour.
  for (const auto& loop : m.boundary_loops()) {
    int l = -1;
    for (int h : loop) l = std::max(l, label[m.from(h)]);
    if (l < 0) throw InputError("a boundary loop of the annulus is in neither given loop");
    for (int h : loop) label[m.from(h)] = l;
  }

  HarmonicCoordinates hc;
  // ---- height: Dirichlet problem on the interior vertices ----
  std::vector<int> idx(nv, -1);
  int ni = 0;
  for (int v = 0; v < nv; ++v) {
    if (label[v] < 0 && m.vertex_halfedge(v) >= 0) idx[v] = ni++;
  }
  hc.height.assign(nv, 0.0);
  for (int v = 0; v < nv; ++v) {
    if (label[v] == 1) hc.height[v] = 1.0;
  }
  if (ni > 0) {
    std::vector<Eigen::Triplet<double>> trip;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(ni);
    std::vector<double> diag(ni, 0.0);
    for (int e = 0; e < m.num_edges(); ++e) {
      const int h = m.edge_halfedge(e);
      const int a = m.from(h), b = m.to(h);
      const double we = w[e];
      for (auto [p, q] : {std::pair{a, b}, std::pair{b, a}}) {
        if (idx[p] < 0) continue;
        diag[idx[p]] += we;
        if (idx[q] >= 0) {
          trip.emplace_back(idx[p], idx[q], -we);
        } else {
          rhs[idx[p]] += we * hc.height[q];
        }
      }
    }
    for (int i = 0; i < ni; ++i) trip.emplace_back(i, i, diag[i]);
    Eigen::SparseMatrix<double> L(ni, ni);
    L.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
    if (solver.info() != Eigen::Success) {
      throw InputError(
          "harmonic height: the cotangent Laplacian cannot be factorised "
          "(degenerate triangles in the winding surface?)");
    }
    const Eigen::VectorXd x = solver.solve(rhs);
    for (int v = 0; v < nv; ++v) {
      if (idx[v] >= 0) hc.height[v] = x[idx[v]];
    }
  }

  // ---- the cut: a dual path from a face on loop 0 to a face on loop 1 (BFS, fewest faces) ----
  auto boundary_edge_of = [&](int f, int loop) {
    for (int k = 0; k < 3; ++k) {
      const int h = 3 * f + k;
      if (m.is_boundary_halfedge(m.twin(h)) && label[m.from(h)] == loop && label[m.to(h)] == loop) {
        return h;
      }
    }
    return -1;
  };
  std::vector<int> parent(nf, -2);
  std::queue<int> queue;
  for (int f = 0; f < nf; ++f) {
    if (boundary_edge_of(f, 0) >= 0) {
      parent[f] = -1;
      queue.push(f);
    }
  }
  int goal = -1;
  while (!queue.empty() && goal < 0) {
    const int f = queue.front();
    queue.pop();
    if (boundary_edge_of(f, 1) >= 0) {
      goal = f;
      break;
    }
    for (int k = 0; k < 3; ++k) {
      const int t = m.twin(3 * f + k);
      if (m.is_boundary_halfedge(t)) continue;
      const int g = m.face(t);
      if (parent[g] != -2) continue;
      parent[g] = 3 * f + k;  // the halfedge of f through which the path leaves f
      queue.push(g);
    }
  }
  if (goal < 0) throw TopologyError("harmonic angle: no face path joins the two boundary loops");
  std::vector<double> jump(m.num_interior_halfedges(), 0.0);
  constexpr double kTwoPi = 2.0 * M_PI;
  {
    const int hb1 = boundary_edge_of(goal, 1);
    jump[hb1] = kTwoPi;  // leaves the last face through loop 1
    int f = goal;
    hc.cut_faces.push_back(f);
    while (parent[f] >= 0) {
      const int g = parent[f];  // leaving halfedge in the previous face
      jump[g] = kTwoPi;
      jump[m.twin(g)] = -kTwoPi;
      f = m.face(g);
      hc.cut_faces.push_back(f);
    }
    jump[boundary_edge_of(f, 0)] = -kTwoPi;  // enters the first face through loop 0
    std::reverse(hc.cut_faces.begin(), hc.cut_faces.end());
  }

  // ---- theta: minimise sum w (theta_to - theta_from + J)^2, theta pinned at one vertex ----
  int pin = -1;
  for (int v = 0; v < nv && pin < 0; ++v) {
    if (m.vertex_halfedge(v) >= 0) pin = v;
  }
  std::vector<int> tidx(nv, -1);
  int nt = 0;
  for (int v = 0; v < nv; ++v) {
    if (v != pin && m.vertex_halfedge(v) >= 0) tidx[v] = nt++;
  }
  hc.theta.assign(nv, 0.0);
  if (nt > 0) {
    std::vector<Eigen::Triplet<double>> trip;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nt);
    std::vector<double> diag(nt, 0.0);
    for (int e = 0; e < m.num_edges(); ++e) {
      const int h = m.edge_halfedge(e);
      const int a = m.from(h), b = m.to(h);
      const double we = w[e], J = jump[h];
      // d/d theta_b: w (theta_b - theta_a + J); d/d theta_a: -w (theta_b - theta_a + J).
      if (tidx[b] >= 0) {
        diag[tidx[b]] += we;
        rhs[tidx[b]] -= we * J;
        if (tidx[a] >= 0) trip.emplace_back(tidx[b], tidx[a], -we);
      }
      if (tidx[a] >= 0) {
        diag[tidx[a]] += we;
        rhs[tidx[a]] += we * J;
        if (tidx[b] >= 0) trip.emplace_back(tidx[a], tidx[b], -we);
      }
    }
    for (int i = 0; i < nt; ++i) trip.emplace_back(i, i, diag[i]);
    Eigen::SparseMatrix<double> L(nt, nt);
    L.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
    if (solver.info() != Eigen::Success) {
      throw InputError(
          "harmonic angle: the cotangent Laplacian cannot be factorised "
          "(degenerate triangles in the winding surface?)");
    }
    const Eigen::VectorXd x = solver.solve(rhs);
    for (int v = 0; v < nv; ++v) {
      if (tidx[v] >= 0) hc.theta[v] = x[tidx[v]];
    }
  }
  hc.face_offset.resize(nf);
  for (int f = 0; f < nf; ++f) {
    hc.face_offset[f] = {0.0, jump[3 * f], jump[3 * f] + jump[3 * f + 1]};
  }

  // ---- orientation (theta along n x grad h) and conformality diagnostic ----
  double orient = 0.0, err = 0.0, area = 0.0;
  for (int f = 0; f < nf; ++f) {
    const Tri& t = m.triangle(f);
    const Vec3 an = m.face_area_vector(f);
    const double A = an.norm();
    if (!(A > 0.0)) continue;
    const Vec3 n = an / A;
    // grad u = sum_k u_k (n x e_k) / (2A), e_k the edge opposite corner k (ccw).
    Vec3 gh = Vec3::Zero(), gt = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = m.position(t[(k + 2) % 3]) - m.position(t[(k + 1) % 3]);
      const Vec3 g = n.cross(e) / (2.0 * A);
      gh += hc.height[t[k]] * g;
      gt += hc.corner_theta(m, f, k) * g;
    }
    orient += A * gt.dot(n.cross(gh));
    if (gh.norm() > 0.0 && gt.norm() > 0.0) {
      const double c = std::clamp(gh.dot(gt) / (gh.norm() * gt.norm()), -1.0, 1.0);
      err += A * std::fabs(std::acos(c) - M_PI / 2);
      area += A;
    }
  }
  if (orient < 0.0) {
    for (double& x : hc.theta) x = -x;
    for (auto& o : hc.face_offset) {
      for (double& x : o) x = -x;
    }
  }
  hc.conformal_error = area > 0.0 ? err / area * 180.0 / M_PI : 0.0;
  hc.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return hc;
}

}  // namespace windplan
