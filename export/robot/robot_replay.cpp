#include "export/robot/robot_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "export/machine/circuit_surfaces.h"
#include "export/machine/kinematics.h"
#include "export/robot/robot_kinematics.h"
#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "geometry/mesh/closest_point.h"

namespace windplan {

namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string at(const RobotProgramTarget& t) { return t.file + ":" + std::to_string(t.line); }

}  // namespace

RobotReplayResult replay_robot_program(const RobotProgram& program, const WindingPlan& plan,
                                       const Mesh& mandrel, const MachineOptions& machine,
                                       const Motion* planned, const ReplayOptions& options,
                                       const std::vector<const Mesh*>& circuit_surfaces) {
  const auto t0 = std::chrono::steady_clock::now();
  const RobotOptions& ro = machine.robot;
  if (!ro.has_arm()) throw ConfigError("machine.robot.arm: replaying a robot program needs an arm");
  if (program.targets.empty()) throw InputError("the robot program has no moves");
  if (mandrel.num_faces() == 0) throw InputError("the mandrel mesh is empty");
  const RobotArm arm(ro);
  const Eigen::Isometry3d positioner = frame6_transform(ro.positioner);
  const Eigen::Isometry3d positioner_inv = positioner.inverse();
  const Eigen::Isometry3d tool_inv = program.tool.inverse();
  const AxisFrame frame = make_axis_frame(plan.axis);
  // The surfaces the links are measured to: the mandrel first, then every other surface a
  // circuit was wound on (a layup's layers), each with its query.
  const CircuitSurfaces surfaces_of = distinct_circuit_surfaces(plan, mandrel, circuit_surfaces);
  const std::vector<const Mesh*>& meshes = surfaces_of.meshes;
  const std::vector<int>& circuit_mesh = surfaces_of.of;  // per circuit: its entry of `meshes`
  std::vector<std::unique_ptr<const ClosestPointQuery>> queries;
  for (const Mesh* m : meshes) queries.push_back(std::make_unique<const ClosestPointQuery>(*m));

  RobotReplayResult r;
  r.targets = static_cast<int>(program.targets.size());
  r.min_link_clearance = std::numeric_limits<double>::infinity();
  r.min_joint_margin = std::numeric_limits<double>::infinity();
  r.min_wrist_angle = std::numeric_limits<double>::infinity();

  // A point of the cell in the mandrel frame at E1 (deg).
  auto to_mandrel = [&](const Vec3& cell, double e1) {
    const Vec3 c = positioner_inv * cell;
    const double th = std::atan2(c.z(), c.y()) - e1 / kDeg;
    const double rad = std::hypot(c.y(), c.z());
    return Vec3(frame.origin + (c.x() - ro.offset) * frame.d +
                rad * (std::cos(th) * frame.u + std::sin(th) * frame.v));
  };

  // The planned eye path and a window that moves along it.
  std::vector<Vec3> path;
  if (planned) {
    for (const MachineState& st : planned->states) path.push_back(st.eye);
  }
  std::size_t near = 0;
  auto eye_deviation = [&](const Vec3& e) {
    auto seg_dist = [&](std::size_t k) {
      if (k + 1 >= path.size()) return (e - path[k]).norm();
      const Vec3 d = path[k + 1] - path[k];
      const double l2 = d.squaredNorm();
      const double s = l2 > 0.0 ? std::clamp((e - path[k]).dot(d) / l2, 0.0, 1.0) : 0.0;
      return (e - (path[k] + s * d)).norm();
    };
    auto search = [&](std::size_t lo, std::size_t hi) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = lo; k < hi; ++k) {
        const double d = seg_dist(k);
        if (d < best) {
          best = d;
          near = k;
        }
      }
      return best;
    };
    const std::size_t lo = near > 20 ? near - 20 : 0;
    double d = search(lo, std::min(path.size(), near + 200));
    // Lost (a link, an edited program, or a path that comes back on itself, as a hoop layer's
    // tie-on turn closes its circle: the window had followed the circle's end and put the targets
    // of its middle 4.95 mm off, just under the 5 mm this used to wait for): everywhere. 0.1 mm is
    // under every tolerance; a program on its plan (0.0001 mm) never searches.
    if (d > 0.1) d = search(0, path.size());
    return d;
  };
  // The joints of every target, in order: each IK is seeded with the previous
  // target's joints (so this pass is serial), and the first target out of reach
  // or past a limit is refused.
  const std::size_t n = program.targets.size();
  std::vector<Joints> joints(n);
  std::vector<int> statuses(n);
  std::vector<Vec3> eye_cells(n), flanges(n), wrists(n);
  // Per target, the entry of `meshes` of the layer in work: the circuit of the nearest planned
  // eye (-1 without a planned motion: the links are measured to every surface, the nearest
  // counts).
  std::vector<int> target_mesh(n, meshes.size() == 1 ? 0 : -1);
  Joints seed = ro.home;
  for (std::size_t i = 0; i < n; ++i) {
    const RobotProgramTarget& t = program.targets[i];
    const Eigen::Isometry3d cell_eye = program.base * t.pose;
    Joints& q = joints[i];
    const bool solved = i == 0 ? arm.inverse_near(cell_eye * tool_inv, ro.home, 0.0, 0.0, &q)
                               : arm.inverse(cell_eye * tool_inv, seed, &q);
    if (!solved) {
      const Vec3 p = cell_eye.translation();
      char buf[120];
      std::snprintf(buf, sizeof buf, " (%.1f, %.1f, %.1f mm in the cell)", p.x(), p.y(), p.z());
      throw InputError(at(t) + ": the target is out of reach of the " + ro.arm_name + buf);
    }
    const std::string past = joint_limit_violation(ro, q);
    if (!past.empty()) throw InputError(at(t) + ": joint " + past);
    statuses[i] = arm.status(q);
    // FK: where the eye, the flange and the wrist really are.
    const Eigen::Isometry3d flange = arm.flange(q);
    eye_cells[i] = (flange * program.tool).translation();
    flanges[i] = flange.translation();
    wrists[i] = arm.wrist_centre(q);
    seed = q;
  }
  // The flange/last link's clearance of every target, independent per target: fixed chunks,
  // every target writing its own slot, so the results do not depend on the threads. Run beside
  // the fibre model below (which does not need it).
  std::vector<double> link_clearance(n);
  auto link_clearances = [&] {
    constexpr int kChunk = 256;
    const int chunks = static_cast<int>((n + kChunk - 1) / kChunk);
    parallel_for_index(chunks, [&](int c) {
      const std::size_t end = std::min(n, static_cast<std::size_t>(c + 1) * kChunk);
      double prev_best = std::numeric_limits<double>::infinity();
      Vec3 prev_point = Vec3::Zero(), best_point = Vec3::Zero();
      int prev_mesh = -2;
      for (std::size_t i = static_cast<std::size_t>(c) * kChunk; i < end; ++i) {
        // The surface of the layer in work (all of them, the nearest counting, when unknown);
        // the previous target's bound holds on the same surface only.
        if (target_mesh[i] != prev_mesh) prev_best = std::numeric_limits<double>::infinity();
        prev_mesh = target_mesh[i];
        const std::size_t m_lo = target_mesh[i] < 0 ? 0 : target_mesh[i];
        const std::size_t m_hi = target_mesh[i] < 0 ? meshes.size() : m_lo + 1;
        // The minimum over 5 points of the link, each query bounded by the best so far and by
        // the previous target's minimum plus how far from its point this one lies (the distance
        // to the mandrel is 1-Lipschitz; 1e-3 mm of slack for rounding): the same minimum as
        // unbounded queries (a bounded query gives the same hit when one is nearer). The first
        // target of a chunk starts unbounded; a miss (rounding) is redone unbounded.
        auto link_min = [&](bool bounded) {
          double best = std::numeric_limits<double>::infinity();
          for (int k = 0; k <= 4; ++k) {
            const Vec3 p =
                to_mandrel(wrists[i] + (flanges[i] - wrists[i]) * (k / 4.0), program.targets[i].e1);
            const double bound =
                bounded ? std::min(best, prev_best + (p - prev_point).norm() + 1e-3) : best;
            for (std::size_t mi = m_lo; mi < m_hi; ++mi) {
              const double b = std::min(bound, best);
              const ClosestPointQuery::Hit h = queries[mi]->closest_within(p, b * b);
              if (h.distance < best) {
                best = h.distance;
                best_point = p;
              }
            }
          }
          return best;
        };
        double best = link_min(true);
        if (!(best < std::numeric_limits<double>::infinity())) best = link_min(false);
        prev_best = best;
        prev_point = best_point;
        link_clearance[i] = best;
      }
    });
  };
  GcodeProgram lathe;
  lathe.inverse_time = true;
  Joints prev_q{};
  int prev_status = -1;
  Vec3 prev_eye = Vec3::Zero();
  double prev_e1 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const RobotProgramTarget& t = program.targets[i];
    const Joints& q = joints[i];
    const int status = statuses[i];
    if (i > 0 && status != prev_status) ++r.configuration_changes;
    const Vec3& eye_cell = eye_cells[i];
    for (int j = 0; j < 6; ++j) {
      const double margin = std::min(q[j] - ro.joints[j].min, ro.joints[j].max - q[j]);
      if (margin < r.min_joint_margin) {
        r.min_joint_margin = margin;
        r.min_joint_margin_joint = ro.joints[j].name;
      }
    }
    r.min_wrist_angle = std::min(r.min_wrist_angle, std::fabs(q[4]));
    // The eye in the positioner frame, in the lathe model's axes.
    const Vec3 c = positioner_inv * eye_cell;
    if (!path.empty()) {
      const Vec3 e = to_mandrel(eye_cell, t.e1);
      const double d = eye_deviation(e);
      if (d > r.max_eye_deviation) {
        r.max_eye_deviation = d;
        r.max_eye_deviation_at = at(t);
      }
      if (meshes.size() > 1) {
        // The nearer end of the nearest planned segment (a layer's first target lies on the
        // segment from the previous layer's last eye).
        std::size_t k = near;
        if (k + 1 < path.size() && (e - path[k + 1]).norm() < (e - path[k]).norm()) ++k;
        const int ordinal = planned->states[k].ordinal;
        target_mesh[i] = ordinal >= 0 && ordinal < static_cast<int>(circuit_mesh.size())
                             ? circuit_mesh[ordinal]
                             : 0;
      }
    }
    double duration = 0.0;
    if (i > 0) {
      double joint_time = std::fabs(t.e1 - prev_e1) / ro.e1_max_velocity;
      for (int j = 0; j < 6; ++j) {
        joint_time = std::max(joint_time, std::fabs(q[j] - prev_q[j]) / ro.joints[j].max_velocity);
      }
      if (t.joint_move) {
        duration = joint_time;
      } else if (t.time >= 0.0) {
        duration = t.time;
      } else {
        duration = std::max((c - prev_eye).norm() / 1000.0 / t.vel_cp,
                            std::fabs(t.e1 - prev_e1) / (ro.e1_max_velocity * t.vel_extax / 100.0));
      }
      if (joint_time < 1e-9) {
        // No joint moves (a target repeated, as where a circuit ends and the
        // next begins).
      } else if (duration > 0.0) {
        const double ratio = joint_time / duration;
        if (ratio > r.max_joint_speed_ratio) {
          r.max_joint_speed_ratio = ratio;
          r.max_joint_speed_at = at(t);
        }
      } else if (joint_time > 0.0) {
        r.max_joint_speed_ratio = std::numeric_limits<double>::infinity();
        r.max_joint_speed_at = at(t);
      }
      r.cycle_time += duration;
    }
    // Pieces of at most 2 mm of eye travel, linear in the BASE frame and in E1.
    const int pieces = (i == 0 || t.joint_move)
                           ? 1
                           : std::max(1, static_cast<int>(std::ceil((c - prev_eye).norm() / 2.0)));
    for (int k = 1; k <= pieces; ++k) {
      const double s = static_cast<double>(k) / pieces;
      const Vec3 e = pieces == 1 ? c : Vec3(prev_eye + s * (c - prev_eye));
      const double e1 = pieces == 1 ? t.e1 : prev_e1 + s * (t.e1 - prev_e1);
      GcodeBlock b;
      b.line = static_cast<int>(i) + 1;
      b.rapid = t.joint_move;
      b.a = e1 - std::atan2(e.z(), e.y()) * kDeg;
      b.x = e.x() - ro.offset;
      b.y = std::hypot(e.y(), e.z());
      b.inverse_time = true;
      b.feed = duration > 0.0 ? 60.0 / (duration / pieces) : 1e9;
      lathe.blocks.push_back(b);
    }
    prev_q = q;
    prev_status = status;
    prev_eye = c;
    prev_e1 = t.e1;
  }
  // The fibre model of the G-code replay, on the equivalent 4-axis blocks; A
  // continuous.
  for (std::size_t k = 1; k < lathe.blocks.size(); ++k) {
    GcodeBlock& b = lathe.blocks[k];
    b.a -= 360.0 * std::round((b.a - lathe.blocks[k - 1].a) / 360.0);
  }
  lathe.ended = true;
  MachineOptions as_lathe = machine;
  as_lathe.kind = "lathe4";
  for (AxisOptions* a : {&as_lathe.a, &as_lathe.x, &as_lathe.y, &as_lathe.b}) {
    a->min = -std::numeric_limits<double>::infinity();
    a->max = std::numeric_limits<double>::infinity();
  }
  parallel_for_index(2, [&](int k) {
    if (k == 0) r.fibre = replay_program(lathe, plan, mandrel, as_lathe, options, circuit_surfaces);
    if (k == 1) link_clearances();
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (link_clearance[i] < r.min_link_clearance) {
      r.min_link_clearance = link_clearance[i];
      r.min_link_clearance_at = at(program.targets[i]);
    }
  }
  const int worst = std::max(1, r.fibre.max_deviation_line);
  const RobotProgramTarget& wt = program.targets[std::min<int>(worst, r.targets) - 1];
  r.max_deviation_at = at(wt);
  r.fibre.max_deviation_line = wt.line;  // the line in its file (max_deviation_at names the file)
  const int cl = std::min<int>(std::max(1, r.fibre.min_clearance_line), r.targets);
  r.fibre.min_clearance_line = program.targets[cl - 1].line;
  r.min_clearance_at = at(program.targets[cl - 1]);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "robot replay: %d targets, deviation max %.3f mm (%s) mean "
                "%.4f mm, eye path %.3f mm "
                "(%s), eye clearance "
                "%.2f mm, flange/last link clearance %.1f mm (%s), joint "
                "margin %.1f deg (%s), "
                "|A5| >= %.1f deg, joint speed ratio %.2f, %d configuration "
                "changes, cycle %.1f s",
                r.targets, r.fibre.max_deviation, r.max_deviation_at.c_str(),
                r.fibre.mean_deviation, r.max_eye_deviation,
                r.max_eye_deviation_at.empty() ? "-" : r.max_eye_deviation_at.c_str(),
                r.fibre.min_clearance, r.min_link_clearance, r.min_link_clearance_at.c_str(),
                r.min_joint_margin, r.min_joint_margin_joint.c_str(), r.min_wrist_angle,
                r.max_joint_speed_ratio, r.configuration_changes, r.cycle_time);
  r.summary = buf;
  return r;
}

bool RobotReplayResult::keeps_clearance(double clearance, std::string* message) const {
  if (!(clearance > 0.0) || !(fibre.min_clearance < clearance - 1e-3)) return true;
  if (message) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  ": the replay puts the eye %.4f mm from the surface it winds on, less than "
                  "machine.envelope.clearance %g mm",
                  fibre.min_clearance, clearance);
    *message = min_clearance_at + buf;
  }
  return false;
}

bool RobotReplayResult::within(double tolerance, ReplayExcess* excess) const {
  const bool eye = max_eye_deviation > fibre.max_deviation;
  const double worst = eye ? max_eye_deviation : fibre.max_deviation;
  if (!(tolerance > 0.0) || !(worst > tolerance)) return true;
  if (excess) {
    *excess = ReplayExcess();
    excess->eye = eye;
    excess->deviation = worst;
    excess->tolerance = tolerance;
    excess->at = eye ? max_eye_deviation_at : max_deviation_at;
  }
  return false;
}

}  // namespace windplan
