// Internal: from the wire (ActuatorCommand, ControlParameters; joints by index)
// to the joint controller, with every field checked. A check returns the
// error text, naming the field and its value (e.g. "modes[2] = 77 is not a
// ControlMode (0 IDLE … 5 PWM)"), or an empty string; on any error nothing of
// the message is applied. Accepted messages do not allocate (buffers reused).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <wbi/msg/commands.h>
#include <wbi/actuation/joint_controller.hpp>

namespace wbi::robot {

// Fills batch from command after checking header.robot (must be `robot`), the
// sizes of modes and references (one per joint), the mode values (in the
// enum) and the references (finite). The joint controller checks the indices
// and repeated joints.
std::string to_batch(const wbi::msg::ActuatorCommand& command, std::string_view robot,
                     const std::vector<double>& reference_speed,
                     actuation::JointCommandBatch& batch);

// Checks control parameters for a robot with `joint_names`: header.robot, at
// least one joint, indices in range and not repeated, kp/ki/kd/reference_speed
// empty or one per joint; gains finite and ≥ 0, speeds finite and > 0; NaN
// means "unchanged" (what wbi_proxy sends for the parameters it does not set).
std::string check_parameters(const wbi::msg::ControlParameters& message, std::string_view robot,
                             const std::vector<std::string>& joint_names);

}  // namespace wbi::robot
