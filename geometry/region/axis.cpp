#include "geometry/region/axis.h"

#include <algorithm>

namespace windplan {

double RadiusProfile::at(double x) const {
  if (axial.empty()) return 0.0;
  if (x <= axial.front()) return radius.front();
  if (x >= axial.back()) return radius.back();
  const auto it = std::upper_bound(axial.begin(), axial.end(), x);
  const std::size_t i = static_cast<std::size_t>(it - axial.begin());
  const double t = (x - axial[i - 1]) / (axial[i] - axial[i - 1]);
  return (1.0 - t) * radius[i - 1] + t * radius[i];
}

}  // namespace windplan
