// The base orientation of a world_H_base argument, checked: both model
// backends need it as a quaternion.
#pragma once

#include <Eigen/Geometry>
#include <wbi/msg/eigen.hpp>

#include "wbi/types.hpp"

namespace wbi::proxy {

// Throws Error when the rotation block is not a rotation matrix.
inline void check_rotation(const Transform& world_H_base) {
  const Eigen::Matrix3d R = world_H_base.topLeftCorner<3, 3>();
  if (!(R.transpose() * R).isIdentity(1e-6) || R.determinant() < 0.0) {
    throw Error("world_H_base: the rotation block is not a rotation matrix");
  }
}

// The checked rotation block as the wire's quaternion (msg::orientation_of).
inline Eigen::Quaterniond base_orientation(const Transform& world_H_base) {
  check_rotation(world_H_base);
  return msg::orientation_of(world_H_base);
}

}  // namespace wbi::proxy
