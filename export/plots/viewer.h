#pragma once
// viewer.html: one self-contained page that shows a plan in 3-D in any WebGL browser, opened from
// disk with no network and no server.
//
// The page holds three scripts: three.js r111 (Debian's libjs-three, embedded at build time by
// export/CMakeLists.txt), the plan's data as JSON (id "windplan-data") and the viewer's own script
// (export/plots/viewer_app.js, also embedded at build time). It shows the mandrel (shaded), the
// circuits as bands of their band width (coloured by circuit, layer, winding angle or slippage
// |k_g/k_n| / mu, with a legend), the cut-lines, the payout eye, its path and the free fibre at a
// chosen time (a slider plays the winding in order; the machine axes' values beside it), per layer
// show/hide, and a panel with the report's headline figures and warnings.
//
// Data: positions in the axis frame of export/machine/kinematics.h (x axial along d, y along u, z
// along v; mm), as base64 little-endian float32 arrays (triangles as uint32). Per dense fibre
// point: position, unit normal, winding angle (deg), slippage. Per machine state: t_s, A, X, Y, B,
// F, eye, fibre point, free length and the index of the dense point it stands on.
//
// Size: when the page would exceed ViewerOptions::max_bytes, the fibre points and machine states
// are thinned by a whole stride (every k-th kept, plus every segment's and circuit's ends) and the
// mandrel by vertex clustering, until it fits; the page then says so in its panel (ViewerPage::
// note). The files beside it (CSV, G-code) always keep every point.
//
// URL hash parameters (for links and the browser test): t=<0..1> (slider, fraction of the wind
// time), mode=circuit|layer|angle|slippage, frame=mandrel|machine, view=<azimuth deg>.
// The page logs "windplan-viewer: frame ..." on the console after each drawn frame and
// "windplan-viewer ERROR: ..." for any script error.
#include <cstddef>
#include <string>

#include "export/machine/kinematics.h"
#include "export/plots/joints_svg.h"
#include "geometry/mesh/mesh.h"
#include "planner/plan/plan.h"

namespace windplan {

struct ViewerOptions {
  std::size_t max_bytes = 5000000;  ///< bytes: the page's size limit (decimated above it)

  /// max_bytes leaves room for the embedded scripts and some data (>= 2 MB).
  bool is_valid(std::string* why) const;
};

struct ViewerPage {
  std::string html;
  int points = 0, points_kept = 0;        ///< dense fibre points: in the plan, on the page
  int states = 0, states_kept = 0;        ///< machine states
  int triangles = 0, triangles_kept = 0;  ///< mandrel triangles
  std::string note;                       ///< decimation note shown in the page; empty: none
};

/// A robot cell's joints for the page's joint panel (robot jobs only; export_plan fills it from
/// the robot motion, as joints.csv): every series (E1, then A1..A6 of the arm; deg, with their
/// limits, none for E1) holds one value per machine state of `motion`, and `time` the robot's
/// time of each (s, joints.csv's t_s). The page then embeds them ("windplan-joints": for every
/// state kept on the page, its planned time, its joints.csv row, the robot's time and the
/// values, as float32) and the joint panel's script (export/plots/viewer_joints.js): at each
/// moment of the slider, each joint's value with a bar over its limits, and the joints against
/// time with a cursor. A page without joints is the same page, byte for byte, as before them.
struct ViewerJoints {
  std::string arm;                  ///< the arm's name, for the panel's heading
  std::vector<double> time;         ///< s, per machine state
  std::vector<JointSeries> series;  ///< E1, A1..A6: per machine state, deg
};

/// The page of a plan. `motion` is the plan's (compute_motion); `mandrel` the mesh the plan was
/// made on; `joints` a robot cell's (nullptr: none). \throw InputError when options are invalid
/// or the joints do not have one value per machine state.
ViewerPage viewer_page(const WindingPlan& plan, const Mesh& mandrel, const Motion& motion,
                       const ViewerOptions& opts = {}, const ViewerJoints* joints = nullptr);

/// The layer of each circuit (in plan order; WindingPlan::layers), as the page and
/// development.svg colour and group them: 0 for every circuit of a plan without layers.
std::vector<int> circuit_layers(const WindingPlan& plan);

/// Band width of circuit k (mm): its layer's, else the plan's.
double circuit_band_width(const WindingPlan& plan, int k);

/// "name (kind, angle deg)" of layer l, for legends; "layer l" without layers.
std::string layer_label(const WindingPlan& plan, int l);

/// RFC 4648 base64 of raw bytes (no line breaks).
std::string base64(const unsigned char* data, std::size_t n);

}  // namespace windplan
