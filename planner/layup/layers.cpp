#include "planner/layup/layers.h"

namespace windplan {

const char* to_string(LayerKind k) { return k == LayerKind::Hoop ? "hoop" : "helical"; }

bool LayerOptions::is_valid(std::string* why) const {
  return kind == LayerKind::Hoop ? hoop.is_valid(why) : winding.is_valid(why);
}

std::vector<LayerOptions> effective_layers(const std::vector<LayerOptions>& layers,
                                           const WindingOptions& winding) {
  if (!layers.empty()) return layers;
  LayerOptions one;
  one.kind = LayerKind::Helical;
  one.name = "helical1";
  one.winding = winding;
  return {one};
}

}  // namespace windplan
