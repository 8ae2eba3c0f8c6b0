#pragma once
// The local starts of geodesic_between (geometry/geodesic/geodesic_between.h): start corridors
// from the Steiner graph and the two edge graphs, each refined, the best kept; and the legs
// between the vertices a path passes, solved on their own. Internal to geometry/geodesic: the
// fallback of the exact window search, and the answer for points that are not vertices and for
// the density and anisotropic metrics.
#include "geometry/geodesic/geodesic_between.h"

namespace windplan {

/// The refinements of the start corridors (see GeodesicOptions), the best one kept.
OpenGeodesicResult best_of_starts(const GeodesicContext& context, const SurfacePoint& a,
                                  const SurfacePoint& b, const GeodesicOptions& options,
                                  const EdgePathOptions& edge_options);

/// split_at_vertices: the legs between the vertices the path passes, solved on their own.
void split_at_passed_vertices(const GeodesicContext& context, const SurfacePoint& a,
                              const SurfacePoint& b, const GeodesicOptions& options,
                              const EdgePathOptions& edge_options, OpenGeodesicResult* result);

}  // namespace windplan
