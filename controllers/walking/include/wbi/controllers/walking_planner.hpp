// The controller type `walking_planner`: a WalkingPlan (walking_plan.hpp)
// chained in a walking controller's host. It commands no joint; its output
// `walk` (kWalkReferenceSize values) feeds the controller's input of the same
// size in the same tick. At activation it stands on the measured feet
// (left_sole, right_sole) and CoM; `goal` = [dx, dy, dyaw in degrees] walks
// there (walk_to): the deploy file's goal start_after_s after activation,
// each later change of value at once (a goal while walking is refused, with
// one line on stdout).
#pragma once

#include "wbi/controllers/walking_plan.hpp"
#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers {

class ControllerRegistry;

void register_walking_planner(ControllerRegistry& registry);

namespace walking {

// The sole `frame` of the robot in `state`, as the plan takes it (stand()).
inline FootPose measured_sole(WholeBodyInterface& robot, const RobotState& state, int frame) {
  Transform pose;
  robot.frame_pose(state.q, state.world_H_base, frame, pose);
  return FootPose::of(pose);
}

}  // namespace walking

}  // namespace wbi::controllers
