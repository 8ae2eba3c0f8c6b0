#include "export/robot/robot_kinematics.h"

#include <cmath>
#include <cstdio>
#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

constexpr double kDeg = 180.0 / M_PI;

KDL::Frame to_kdl(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d& r = t.linear();
  return KDL::Frame(KDL::Rotation(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0),
                                  r(2, 1), r(2, 2)),
                    KDL::Vector(t.translation().x(), t.translation().y(), t.translation().z()));
}

Eigen::Isometry3d from_kdl(const KDL::Frame& f) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) t.linear()(i, j) = f.M(i, j);
    t.translation()(i) = f.p(i);
  }
  return t;
}

}  // namespace

Eigen::Isometry3d frame6_transform(const Frame6& f) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(f.abc[0] / kDeg, Vec3::UnitZ()) *
                Eigen::AngleAxisd(f.abc[1] / kDeg, Vec3::UnitY()) *
                Eigen::AngleAxisd(f.abc[2] / kDeg, Vec3::UnitX()))
                   .toRotationMatrix();
  t.translation() = Vec3(f.xyz[0], f.xyz[1], f.xyz[2]);
  return t;
}

std::array<double, 3> rotation_abc(const Eigen::Matrix3d& r) {
  const double b = std::atan2(-r(2, 0), std::hypot(r(0, 0), r(1, 0)));
  double a = 0.0, c = 0.0;
  if (std::hypot(r(0, 0), r(1, 0)) > 1e-12) {
    a = std::atan2(r(1, 0), r(0, 0));
    c = std::atan2(r(2, 1), r(2, 2));
  } else {  // gimbal lock: put all of the rotation about z into A
    a = std::atan2(-r(0, 1), r(1, 1));
  }
  return {a * kDeg, b * kDeg, c * kDeg};
}

struct RobotArm::Kdl {
  KDL::Chain chain;        // base to flange
  KDL::Chain wrist_chain;  // base to the A5 joint
  std::unique_ptr<KDL::ChainFkSolverPos_recursive> fk, fk_wrist;
  std::unique_ptr<KDL::ChainIkSolverVel_pinv> vel;
  std::unique_ptr<KDL::ChainIkSolverPos_NR> nr;
  std::unique_ptr<KDL::ChainIkSolverPos_LMA> lma;
  std::unique_ptr<KDL::ChainJntToJacSolver> jac;
};

RobotArm::RobotArm(const RobotOptions& robot) : robot_(robot), kdl_(std::make_unique<Kdl>()) {
  if (robot.joints.size() != 6) {
    throw ConfigError("machine.robot.arm: the arm needs 6 joints (got " +
                      std::to_string(robot.joints.size()) + ")");
  }
  for (int i = 0; i < 6; ++i) {
    const RobotJoint& j = robot.joints[i];
    const KDL::Segment offset(KDL::Joint(KDL::Joint::Fixed),
                              KDL::Frame(KDL::Vector(j.origin[0], j.origin[1], j.origin[2])));
    const KDL::Segment turn(
        j.name, KDL::Joint(j.name, KDL::Vector(0, 0, 0),
                           KDL::Vector(j.axis[0], j.axis[1], j.axis[2]), KDL::Joint::RotAxis));
    kdl_->chain.addSegment(offset);
    kdl_->chain.addSegment(turn);
    if (i < 4) {
      kdl_->wrist_chain.addSegment(offset);
      kdl_->wrist_chain.addSegment(turn);
    } else if (i == 4) {
      kdl_->wrist_chain.addSegment(offset);
    }
  }
  kdl_->chain.addSegment(
      KDL::Segment(KDL::Joint(KDL::Joint::Fixed),
                   KDL::Frame(KDL::Vector(robot.flange[0], robot.flange[1], robot.flange[2]))));
  kdl_->fk = std::make_unique<KDL::ChainFkSolverPos_recursive>(kdl_->chain);
  kdl_->fk_wrist = std::make_unique<KDL::ChainFkSolverPos_recursive>(kdl_->wrist_chain);
  kdl_->vel = std::make_unique<KDL::ChainIkSolverVel_pinv>(kdl_->chain, 1e-12, 300);
  kdl_->nr =
      std::make_unique<KDL::ChainIkSolverPos_NR>(kdl_->chain, *kdl_->fk, *kdl_->vel, 100, 1e-12);
  Eigen::Matrix<double, 6, 1> w;
  w << 1.0, 1.0, 1.0, 1e6, 1e6, 1e6;  // mm against radians: 1 mrad ~ 1 mm at 1 m
  kdl_->lma = std::make_unique<KDL::ChainIkSolverPos_LMA>(kdl_->chain, w, 1e-12, 1000, 1e-15);
  kdl_->jac = std::make_unique<KDL::ChainJntToJacSolver>(kdl_->chain);
  const auto& o = robot.joints[3].origin;
  phi_deg_ = std::atan2(o[2], o[0]) * kDeg;  // A3 that puts the A4 origin on the A2-A3 line
}

RobotArm::~RobotArm() = default;

Eigen::Isometry3d RobotArm::flange(const Joints& q) const {
  KDL::JntArray j(6);
  for (int i = 0; i < 6; ++i) j(i) = q[i] / kDeg;
  KDL::Frame f;
  kdl_->fk->JntToCart(j, f);
  return from_kdl(f);
}

Vec3 RobotArm::wrist_centre(const Joints& q) const {
  KDL::JntArray j(4);
  for (int i = 0; i < 4; ++i) j(i) = q[i] / kDeg;
  KDL::Frame f;
  kdl_->fk_wrist->JntToCart(j, f);
  return Vec3(f.p.x(), f.p.y(), f.p.z());
}

bool RobotArm::inverse(const Eigen::Isometry3d& target, const Joints& seed, Joints* q) const {
  KDL::JntArray s(6), out(6);
  for (int i = 0; i < 6; ++i) s(i) = seed[i] / kDeg;
  const KDL::Frame t = to_kdl(target);
  auto accept = [&](const KDL::JntArray& j) {
    Joints r;
    for (int i = 0; i < 6; ++i) r[i] = j(i) * kDeg;
    const Eigen::Isometry3d f = flange(r);
    const double dp = (f.translation() - target.translation()).norm();
    // ~ the rotation angle (rad); acos of the trace would lose half the digits near 0.
    const double dr = (f.linear() - target.linear()).norm() / std::sqrt(2.0);
    if (!(dp < 1e-6 && dr < 1e-8)) return false;
    // The solvers work modulo 2 pi: keep each joint the turn nearest the seed.
    for (int i = 0; i < 6; ++i) r[i] -= 360.0 * std::round((r[i] - seed[i]) / 360.0);
    *q = r;
    return true;
  };
  // KDL measures the rotation error through an acos (about 1e-8 rad at best): Newton steps on
  // the chain's Jacobian with the skew part of the rotation error finish the solution, at most
  // `steps`, stopping once the error is down to rounding (1e-11 mm, 1e-14 rad: two to three
  // orders above the floor of an arm's coordinates, about 1e-13 mm, and far below the 1e-6 mm
  // that accept asks; a step from there moves no joint by more than rounding).
  auto polish = [&](KDL::JntArray* j, int steps) {
    KDL::Jacobian jac(6);
    for (int it = 0; it < steps; ++it) {
      KDL::Frame f;
      kdl_->fk->JntToCart(*j, f);
      const Eigen::Isometry3d fe = from_kdl(f);
      const Eigen::Matrix3d e = target.linear() * fe.linear().transpose();
      Eigen::Matrix<double, 6, 1> err;
      err.head<3>() = target.translation() - fe.translation();
      err.tail<3>() = 0.5 * Vec3(e(2, 1) - e(1, 2), e(0, 2) - e(2, 0), e(1, 0) - e(0, 1));
      if (err.head<3>().norm() < 1e-11 && err.tail<3>().norm() < 1e-14) return;
      kdl_->jac->JntToJac(*j, jac);
      const Eigen::Matrix<double, 6, 6> jm = jac.data;
      const Eigen::Matrix<double, 6, 1> dq = jm.completeOrthogonalDecomposition().solve(err);
      for (int i = 0; i < 6; ++i) (*j)(i) += dq(i);
    }
  };
  // From a seed near the solution (the previous target's joints, as along a path), Newton steps
  // on the chain's Jacobian alone converge (quadratically: from 3 mm off, 1e-2, 1e-8, 1e-13 mm)
  // in a few steps: tried first, ten times cheaper than KDL's solvers, whose stopping tests
  // (mixing mm and radians) run them to their iteration limits. The result is judged by FK
  // above either way.
  {
    KDL::JntArray j = s;
    polish(&j, 9);
    if (accept(j)) return true;
  }
  // The solvers' own stopping tests mix mm and radians: the result is judged by FK above.
  kdl_->nr->CartToJnt(s, t, out);
  polish(&out, 3);
  if (accept(out)) return true;
  KDL::JntArray lma(6);
  kdl_->lma->CartToJnt(s, t, lma);
  polish(&lma, 3);
  if (accept(lma)) return true;
  kdl_->nr->CartToJnt(lma, t, out);  // Newton-Raphson from what LMA brought close
  polish(&out, 3);
  return accept(out);
}

bool RobotArm::inverse_near(const Eigen::Isometry3d& target, const Joints& home, double margin,
                            double wrist, Joints* q, bool any) const {
  const Vec3 p = target.translation();
  const Vec3 ax(robot_.joints[0].axis[0], robot_.joints[0].axis[1], robot_.joints[0].axis[2]);
  const double a1 = std::atan2(p.y(), p.x()) * kDeg * (ax.z() < 0.0 ? -1.0 : 1.0);
  bool found = false;
  double best = 0.0;
  for (double a2 : {-90.0, -60.0, -30.0, -120.0}) {
    for (double a3 : {90.0, 60.0, 120.0, 30.0}) {
      for (double a5 : {45.0, -45.0, 90.0, -90.0}) {
        for (double a4 : {0.0, 90.0, -90.0, 180.0}) {
          const Joints seed{a1, a2, a3, a4, a5, home[5]};
          Joints got;
          if (!inverse(target, seed, &got)) continue;
          // The turn of A4 and A6 nearest home.
          for (int i : {3, 5}) got[i] -= 360.0 * std::round((got[i] - home[i]) / 360.0);
          if (!joint_limit_violation(robot_, got, margin).empty()) continue;
          if (std::fabs(got[4]) < wrist) continue;
          double d = 0.0;
          for (int i = 0; i < 6; ++i) d += (got[i] - home[i]) * (got[i] - home[i]);
          if (!found || d < best) {
            found = true;
            best = d;
            *q = got;
          }
          if (any) return true;
        }
      }
    }
  }
  return found;
}

int RobotArm::status(const Joints& q) const {
  int st = 0;
  const Vec3 w = wrist_centre(q);
  const double a1 = q[0] / kDeg;
  const Vec3 ax(robot_.joints[0].axis[0], robot_.joints[0].axis[1], robot_.joints[0].axis[2]);
  // x of the wrist centre in the frame turned by A1 (about the A1 axis, sign included).
  const Vec3 fwd = Eigen::AngleAxisd(a1, ax) * Vec3::UnitX();
  if (w.dot(fwd) < 0.0) st |= 1;
  if (q[2] >= phi_deg_) st |= 2;
  if (q[4] <= 0.0) st |= 4;
  return st;
}

int RobotArm::turn(const Joints& q) {
  int t = 0;
  for (int i = 0; i < 6; ++i) {
    if (q[i] < 0.0) t |= 1 << i;
  }
  return t;
}

std::string joint_limit_violation(const RobotOptions& robot, const Joints& q, double margin) {
  for (int i = 0; i < 6 && i < static_cast<int>(robot.joints.size()); ++i) {
    const RobotJoint& j = robot.joints[i];
    const bool low = q[i]<j.min + margin, high = q[i]> j.max - margin;
    if (low || high) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s = %.3f deg past its limit %g deg", j.name.c_str(), q[i],
                    low ? j.min : j.max);
      std::string msg = buf;
      if (margin > 0.0) {
        std::snprintf(buf, sizeof buf, " less a margin of %g deg", margin);
        msg += buf;
      }
      return msg;
    }
  }
  return "";
}

}  // namespace windplan
