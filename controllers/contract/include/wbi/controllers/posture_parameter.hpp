// A controller's postural reference as a parameter: per joint, optional; when
// unset, the joint positions measured at configure.
#pragma once

#include <Eigen/Core>

#include "wbi/controllers/parameter_table.hpp"
#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers {

inline ParameterSpec posture_parameter() {
  return {.name = "posture",
          .unit = "rad",
          .help = "postural task's reference (default: measured at configure)",
          .size = kPerJoint,
          .live = false,
          .optional = true};
}

// At configure: the `posture` parameter's values, or the measured joints.
inline Eigen::VectorXd read_posture(WholeBodyInterface& robot, const ParameterTable& parameters) {
  Eigen::VectorXd posture(robot.dofs());
  if (const std::size_t i = parameters.index("posture"); parameters.is_set(i)) {
    posture = Eigen::Map<const Eigen::VectorXd>(parameters.values(i).data(), robot.dofs());
  } else {
    robot.read_estimates(EstimateKind::joint_position, posture);
  }
  return posture;
}

}  // namespace wbi::controllers
