// What the CoM references measure on the robot (com_sinusoid.hpp's inputs):
// the CoM and the middle of the two soles at a state, through the whole-body
// interface. Shared by the generator component and the chained planner.
#pragma once

#include <Eigen/Core>

#include <wbi/whole_body_interface.hpp>

namespace wbi::controllers {

inline Eigen::Vector3d measured_com(WholeBodyInterface& robot, const RobotState& state) {
  Eigen::Vector3d c;
  robot.com(state.q, state.world_H_base, c);
  return c;
}

// sole_pose: a buffer (no allocation).
inline Eigen::Vector3d feet_center(WholeBodyInterface& robot, const RobotState& state, int left,
                                   int right, Transform& sole_pose) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const int sole : {left, right}) {
    robot.frame_pose(state.q, state.world_H_base, sole, sole_pose);
    sum += sole_pose.topRightCorner<3, 1>();
  }
  return 0.5 * sum;
}

}  // namespace wbi::controllers
