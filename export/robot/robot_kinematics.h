#pragma once
// Kinematics of a 6-axis arm (planner/job/robot_options.h) through Orocos KDL: forward
// kinematics of the flange and inverse kinematics by Newton-Raphson on the chain's Jacobian
// (KDL::ChainIkSolverPos_NR with the pseudo-inverse velocity solver), seeded with the previous
// solution so that consecutive targets stay in one configuration; when that does not converge,
// KDL's Levenberg-Marquardt solver (ChainIkSolverPos_LMA) from the same seed. A solution is
// accepted when FK of it is within 1e-6 mm and 1e-8 rad of the target.
//
// Units: mm and degrees at this interface (KDL works in mm and radians inside).
// Configuration (KUKA's Status bits, written to KRL's S and used for RAPID's cfx): bit 0 = the
// wrist centre is behind A1 (x < 0 in the frame turned by A1), bit 1 = A3 >= phi (phi the A3 at
// which the forearm's wrist centre is in line with A2-A3: -atan2(-z, x) of the A4 origin), bit 2 =
// A5 <= 0. Turn (KRL's T): bit i set when joint i+1 < 0.
#include <array>
#include <memory>
#include <string>

#include "geometry/mesh/mesh.h"
#include "planner/job/robot_options.h"

namespace windplan {

using Joints = std::array<double, 6>;  ///< deg, A1..A6

/// A rigid transform (mm) from a Frame6 (KUKA A, B, C in degrees: R = Rz(A) Ry(B) Rx(C)).
Eigen::Isometry3d frame6_transform(const Frame6& f);
/// KUKA A, B, C (deg) of a rotation: R = Rz(A) Ry(B) Rx(C), B in [-90, 90].
std::array<double, 3> rotation_abc(const Eigen::Matrix3d& r);

/// An arm built from the robot options (joints, flange).
class RobotArm {
 public:
  /// \throw ConfigError when the options have no 6-joint arm
  explicit RobotArm(const RobotOptions& robot);
  ~RobotArm();
  RobotArm(const RobotArm&) = delete;
  RobotArm& operator=(const RobotArm&) = delete;

  /// The flange pose in the robot's base frame.
  Eigen::Isometry3d flange(const Joints& q) const;
  /// The wrist centre (the A5 joint's origin) in the base frame.
  Vec3 wrist_centre(const Joints& q) const;
  /// Solves q with flange(q) = target, from `seed`. Returns false when neither solver converges
  /// (the target is out of reach or the seed too far). Joint limits are not imposed here:
  /// check_joint_limits does.
  bool inverse(const Eigen::Isometry3d& target, const Joints& seed, Joints* q) const;
  /// Solves a target with no previous joints: Newton-Raphson from a grid of seeds (A1 towards the
  /// target; A2, A3, A5 over their usual ranges); of the solutions inside the limits less
  /// `margin` and with |A5| >= `wrist`, the one nearest `home` (sum of squared deg), or with
  /// `any` the first found (a reach test). False: none.
  bool inverse_near(const Eigen::Isometry3d& target, const Joints& home, double margin,
                    double wrist, Joints* q, bool any = false) const;
  /// Status and Turn (see the header comment).
  int status(const Joints& q) const;
  static int turn(const Joints& q);
  const RobotOptions& options() const { return robot_; }

 private:
  struct Kdl;
  RobotOptions robot_;
  std::unique_ptr<Kdl> kdl_;
  double phi_deg_ = 0.0;
};

/// The first joint outside its limits (margin deg inside them), as "A3 = -140.000 deg past its
/// limit -130 deg"; empty when all are inside.
std::string joint_limit_violation(const RobotOptions& robot, const Joints& q, double margin = 0.0);

}  // namespace windplan
