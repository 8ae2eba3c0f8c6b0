#pragma once
// The `layers:` job section: the laminate as an ordered list of layers, innermost first, each
// wound on the surface built by the layers under it (docs/config.md).
//
// Each layer has a kind and its own keys; what it does not give is taken from the job's
// `winding:` section:
//   helical: the keys of `winding:` (turns, circuits, band_width, beta, mu, stations, ...),
//   hoop:    band_width and mu (from `winding:`), range, overlap, passes, reversal_friction,
//            point_spacing, meridians (planner/layup/hoop.h).
// A job without `layers:` is one helical layer made of `winding:` (every older job keeps working).
#include <string>
#include <vector>

#include "planner/layup/hoop.h"
#include "planner/winding/winding_options.h"

namespace windplan {

enum class LayerKind { Helical, Hoop };

const char* to_string(LayerKind k);

struct LayerOptions {
  LayerKind kind = LayerKind::Helical;
  /// Name in reports, comments and FEA arrays; default "<kind><position>" ("hoop1", "helical2").
  std::string name;
  /// Helical: the layer's winding keys (defaults: the job's `winding:`).
  WindingOptions winding;
  /// Hoop: the layer's keys (band_width and mu default to the job's `winding:`).
  HoopOptions hoop;

  /// The band width the layer winds with (mm).
  double band_width() const {
    return kind == LayerKind::Hoop ? hoop.band_width : winding.band_width;
  }
  bool is_valid(std::string* why) const;
};

/// The layers of a job: its `layers:`, or one helical layer made of `winding` when there are none.
std::vector<LayerOptions> effective_layers(const std::vector<LayerOptions>& layers,
                                           const WindingOptions& winding);

}  // namespace windplan
