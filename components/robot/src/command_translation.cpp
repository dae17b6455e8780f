#include "command_translation.hpp"

namespace wbi::robot {

actuation::ControlMode to_mode(wbi::msg::ControlMode mode) {
  switch (mode) {
    case wbi::msg::ControlMode::IDLE:
      return actuation::ControlMode::kIdle;
    case wbi::msg::ControlMode::POSITION:
      return actuation::ControlMode::kPosition;
    case wbi::msg::ControlMode::POSITION_DIRECT:
      return actuation::ControlMode::kPositionDirect;
    case wbi::msg::ControlMode::VELOCITY:
      return actuation::ControlMode::kVelocity;
    case wbi::msg::ControlMode::TORQUE:
      return actuation::ControlMode::kTorque;
    case wbi::msg::ControlMode::PWM:
      return actuation::ControlMode::kPwm;
  }
  return actuation::ControlMode::kIdle;
}

std::string to_batch(const wbi::msg::ActuatorCommand& command,
                     const std::vector<double>& reference_speed,
                     actuation::JointCommandBatch& batch) {
  const auto& joints = command.joints();
  if (command.modes().size() != joints.size() || command.references().size() != joints.size()) {
    return std::to_string(joints.size()) + " joints but " + std::to_string(command.modes().size()) +
           " modes and " + std::to_string(command.references().size()) + " references";
  }
  batch.joint_indices.resize(joints.size());  // indices: the controller checks their range
  batch.modes.resize(joints.size());
  batch.values.resize(joints.size());
  batch.reference_speeds.resize(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    batch.joint_indices[k] = joints[k];
    batch.modes[k] = to_mode(command.modes()[k]);
    batch.values[k] = command.references()[k];
    batch.reference_speeds[k] =
        joints[k] < reference_speed.size() ? reference_speed[joints[k]] : reference_speed.front();
  }
  return {};
}

}  // namespace wbi::robot
