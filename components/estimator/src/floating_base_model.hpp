// Shared by the base estimators: the robot's model with a floating base, and
// the base part of a model configuration.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <wbi/model/algorithms.hpp>

namespace wbi::estimator::detail {

// The URDF's model with the joints in the robot's order; a fixed base is an error.
inline wbi::model::Model load_floating_base_model(const std::string& urdf,
                                                  const std::vector<std::string>& joints) {
  wbi::model::LoadOptions options;
  options.joints = joints;
  auto model = wbi::model::load_urdf_file(urdf, options);
  if (!model.floating_base) {
    throw std::invalid_argument(urdf + ": a fixed-base robot has no base state to estimate");
  }
  return model;
}

// Writes position and orientation (w, x, y, z) into the first 7 entries of q_model.
inline void set_base(Eigen::VectorXd& q_model, const Eigen::Vector3d& position,
                     const Eigen::Matrix3d& orientation) {
  const Eigen::Quaterniond o(orientation);
  q_model.head<3>() = position;
  q_model.segment<4>(3) << o.w(), o.x(), o.y(), o.z();
}

inline void set_base(Eigen::VectorXd& q_model, const Eigen::Matrix4d& world_H_base) {
  set_base(q_model, world_H_base.topRightCorner<3, 1>(),
           Eigen::Matrix3d(world_H_base.topLeftCorner<3, 3>()));
}

}  // namespace wbi::estimator::detail
