#pragma once
// joints.svg: a robot cell's joints against time (E1 of the positioner, A1..A6 of the arm; from
// export/robot/robot_motion.h via export_plan), one panel each like axes.svg
// (export/plots/axes_svg.h): each panel scaled to its own range, the min and max of the samples
// per pixel column drawn, and a joint limit inside the panel's range drawn as a dashed red line.
// Deterministic text. Elements for readers: <g class="panel" data-joint="E1|A1|..."> each with
// one <polyline>.
#include <limits>
#include <string>
#include <vector>

namespace windplan {

struct JointSeries {
  std::string name;                                       ///< e.g. A1
  std::vector<double> values;                             ///< deg, one per time
  double min = -std::numeric_limits<double>::infinity();  ///< deg, travel limits
  double max = std::numeric_limits<double>::infinity();
};

/// \param t s, increasing, one per sample of every series
std::string joints_svg(const std::vector<double>& t, const std::vector<JointSeries>& joints,
                       const std::string& job_name, int width = 1100, int panel_height = 80);

}  // namespace windplan
