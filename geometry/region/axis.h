#pragma once
// The spindle axis of a mandrel and its radius profile along that axis.
//
// The spindle axis is a line (origin, unit direction) in the mandrel frame (the frame of the
// mesh). The "axial position" of a point p is (p - origin) . direction, its "radius" the distance
// from the axis line. Units: mm.
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

/// The spindle (mandrel rotation) axis.
struct SpindleAxis {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();  ///< unit vector
  /// Axial coordinate of p (mm).
  double axial(const Vec3& p) const { return (p - origin).dot(direction); }
  /// Distance of p from the axis line (mm).
  double radius(const Vec3& p) const {
    const Vec3 d = p - origin;
    return (d - d.dot(direction) * direction).norm();
  }
};

/// The mandrel's radius as a function of the axial coordinate (the largest radius of the mesh at
/// each station), sampled at increasing axial stations. Used for the clearance envelope.
struct RadiusProfile {
  std::vector<double> axial;   ///< mm, strictly increasing
  std::vector<double> radius;  ///< mm, same size
  /// Piecewise-linear interpolation, clamped at the ends; 0 for an empty profile.
  double at(double x) const;
  bool empty() const { return axial.empty(); }
};

}  // namespace windplan
