// Internal: from the wire (ActuatorCommand, ControlParameters; joints by index)
// to the joint controller (batches by joint name). Buffers are reused.
#pragma once

#include <string>

#include <wbi/msg/commands.h>
#include <wbi/actuation/joint_controller.hpp>

namespace wbi::robot {

// Fills batch from command (joints by index: no name lookup per command);
// returns an error text when the sizes disagree, else empty. The joint
// controller checks the indices; on any error nothing is applied.
std::string to_batch(const wbi::msg::ActuatorCommand& command,
                     const std::vector<double>& reference_speed,
                     actuation::JointCommandBatch& batch);

actuation::ControlMode to_mode(wbi::msg::ControlMode mode);

}  // namespace wbi::robot
