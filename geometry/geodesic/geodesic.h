#pragma once
// The geodesic core: refines a surface path into an as-short-as-possible path.
//
// After Liu, Chen, Xin, He, Liu, Zhao, "An Optimization-Driven Approach for Computing Geodesic
// Paths on Triangle Meshes" (eq. 1-8, Algorithm 1). The path is the sequence of edges it crosses
// (geometry/mesh/surface_path.h); the crossing parameters l_i in [0, 1] minimise the total length
// under a per-face metric (geometry/geodesic/path_metric.h: Euclidean, density, anisotropic) plus
// penalty terms for constraints (geometry/geodesic/path_constraint.h). When l_i reaches 0 or 1 the
// path touches a vertex; the face strip is then rerouted around that vertex when the path wants to
// pass it on the other side (for the Euclidean metric: the angle on the current side is >= pi and
// the angle on the other side is < pi), lifted off the vertex when the current side's angle is <
// pi, and otherwise pinned there (a geodesic through a saddle vertex).
//
// Beyond the paper: inside a fixed strip the objective is convex with a tridiagonal Hessian
// (cyclic for loops; bordered by the constraint's extra variables), so a projected Newton step
// costs O(k) for k crossings and converges quadratically. Solver::Newton is the default;
// Solver::Lbfgs is the paper's projected L-BFGS.
//
// Globally shortest (geodesic_between, Euclidean metric, both endpoints at vertices): the
// refinement only finds the locally shortest geodesic of the corridor it starts in, and the
// local starts (two edge-graph paths, the legs between the vertices passed) missed the global
// one on 4 to 10 of 50 random pairs per benchmark mesh, every time in another corridor (8e-6
// to 9e-2 of the length away), so no tighter tolerance could help. An exact window
// propagation (geometry/geodesic/geodesic_windows.h: Chen-Han/ICH windows that cut each other per
// edge, searched as A* towards the target) therefore runs first and returns the shortest path's
// corridor, which the refinement straightens; the local starts are the fallback past
// GeodesicOptions::max_windows or when that refinement does not converge. 50 of 50 pairs are
// exact on all four benchmark meshes at 0.23-0.42x FlipOut's median time per path
// (bench/README.md, session 6).
//
// The core's public interface, one header each:
//   geodesic_options.h   options, summary (termination as data), results
//   refine_path.h        the local refinement (refine_path, its objective, vertex passages)
//   geodesic_between.h   GeodesicContext and geodesic_between (window search first, local starts)
//   geodesic_windows.h   the exact window search; start_search.h the local starts (internal)
#include "geometry/geodesic/geodesic_between.h"
#include "geometry/geodesic/geodesic_options.h"
#include "geometry/geodesic/refine_path.h"
