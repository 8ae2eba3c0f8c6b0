#pragma once
// Start loops for the girth (planner/girth/girth.h) in other corridors than the shortest edge loop.
//
// The girth loop through p is the shortest loop through p winding once; a local method refines
// the corridor it starts in, and the shortest edge loop (a few per cent longer than the loop it
// approximates) can lie in the corridor of a longer local loop: on a bulge next to a neck, the
// bulge's parallel circle through p against the loop that runs down to the neck, around it and
// back. On the seam-lifted double cover (nodes (v, c), an edge across the seam flips c), the
// shortest edge loop through p via vertex q has length D(q) = d((p,0),(q,0)) + d((p,0),(q,1)),
// since d((q,0),(p,1)) = d((p,0),(q,1)) by the cover's symmetry; D is smallest (and flat) along
// the shortest edge loop, and every other corridor's loops show up as further local minima of D.
#include <vector>

#include "geometry/geodesic/edge_path.h"
#include "geometry/mesh/mesh.h"

namespace windplan {

/// Up to `max_loops` edge loops through vertex p (each p, v_1, ..., v_{m-1}, p not repeated),
/// shortest first, through local minima q of D with D(q) <= window * min D, each in another
/// corridor than `first` and than the loops before it (q not on or next to them).
/// \param shift per CSR entry of `graph`: the seam crossing of the directed edge (0: none)
std::vector<std::vector<int>> alternative_edge_loops(const Mesh& mesh, const EdgeGraph& graph,
                                                     const std::vector<signed char>& shift, int p,
                                                     const std::vector<int>& first, int max_loops,
                                                     double window);

}  // namespace windplan
