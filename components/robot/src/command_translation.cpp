#include "command_translation.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include <wbi/msg/wire_vocabulary.hpp>

namespace wbi::robot {

namespace {

// "nan", "inf", "-1e+12", "0.5": a value as an error text shows it.
std::string format(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// "header.robot 'x' is not this robot ('arm')", or empty when it is.
std::string check_robot(const wbi::msg::Header& header, std::string_view robot) {
  if (std::string_view(header.robot().c_str(), header.robot().size()) == robot) {
    return {};
  }
  return "header.robot '" + header.robot().to_string() + "' is not this robot ('" +
         std::string(robot) + "')";
}

std::string element(const char* field, std::size_t k) {
  return std::string(field) + "[" + std::to_string(k) + "]";
}

}  // namespace

std::string to_batch(const wbi::msg::ActuatorCommand& command, std::string_view robot,
                     const std::vector<double>& reference_speed,
                     actuation::JointCommandBatch& batch) {
  if (auto error = check_robot(command.header(), robot); !error.empty()) {
    return error;
  }
  const auto& joints = command.joints();
  if (joints.empty()) {
    return "joints is empty: the command names no joint";
  }
  if (command.modes().size() != joints.size() || command.references().size() != joints.size()) {
    return std::to_string(joints.size()) + " joints but " + std::to_string(command.modes().size()) +
           " modes and " + std::to_string(command.references().size()) + " references";
  }
  batch.joint_indices.resize(joints.size());  // indices: the controller checks their range
  batch.modes.resize(joints.size());
  batch.values.resize(joints.size());
  batch.reference_speeds.resize(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const auto mode = msg::from_wire(command.modes()[k]);
    if (!mode) {
      return element("modes", k) + " = " +
             std::to_string(static_cast<std::uint32_t>(command.modes()[k])) +
             " is not a ControlMode (" + enum_values_text<ControlMode>() + ")";
    }
    batch.modes[k] = *mode;
    const double value = command.references()[k];
    if (!std::isfinite(value)) {
      return element("references", k) + " = " + format(value) + " is not finite";
    }
    batch.joint_indices[k] = joints[k];
    batch.values[k] = value;
    batch.reference_speeds[k] =
        joints[k] < reference_speed.size() ? reference_speed[joints[k]] : reference_speed.front();
  }
  batch.joints.clear();
  return {};
}

std::string check_parameters(const wbi::msg::ControlParameters& message, std::string_view robot,
                             const std::vector<std::string>& joint_names) {
  if (auto error = check_robot(message.header(), robot); !error.empty()) {
    return error;
  }
  const auto& joints = message.joints();
  if (joints.empty()) {
    return "joints is empty: the parameters name no joint";
  }
  struct Field {
    const char* name;
    const std::vector<double>& values;
    bool positive;  // > 0, else ≥ 0
  };
  const Field fields[] = {{"kp", message.kp(), false},
                          {"ki", message.ki(), false},
                          {"kd", message.kd(), false},
                          {"reference_speed", message.reference_speed(), true}};
  bool any = false;
  for (const Field& field : fields) {
    if (!field.values.empty() && field.values.size() != joints.size()) {
      return std::string(field.name) + " has " + std::to_string(field.values.size()) +
             " values for " + std::to_string(joints.size()) + " joints";
    }
    any = any || !field.values.empty();
  }
  if (!any) {
    return "kp, ki, kd and reference_speed are all empty: the parameters set nothing";
  }
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (joints[k] >= joint_names.size()) {
      return "joint index " + std::to_string(joints[k]) + " out of range (the robot has " +
             std::to_string(joint_names.size()) + " joints)";
    }
    for (std::size_t e = 0; e < k; ++e) {
      if (joints[e] == joints[k]) {
        return "joint '" + joint_names[joints[k]] + "' appears twice (joints[" + std::to_string(e) +
               "] and joints[" + std::to_string(k) + "])";
      }
    }
    for (const Field& field : fields) {
      if (field.values.empty() || std::isnan(field.values[k])) {
        continue;  // NaN: unchanged
      }
      const double value = field.values[k];
      const bool ok = std::isfinite(value) && (field.positive ? value > 0.0 : value >= 0.0);
      if (!ok) {
        return element(field.name, k) + " = " + format(value) + " for joint '" +
               joint_names[joints[k]] + "' must be finite and " + (field.positive ? "> 0" : "≥ 0") +
               " (NaN: unchanged)";
      }
    }
  }
  return {};
}

}  // namespace wbi::robot
