// How a joint is controlled: the one control-mode enum of every layer (the
// whole-body interface, the joint controller, the robot's command checks), and
// the wire's (idl/commands.idl, ControlMode), which follows it value for value.
#pragma once

#include <cstdint>

#include "wbi/vocabulary/enum_names.hpp"

namespace wbi {

enum class ControlMode : std::uint8_t {
  idle,      // no control: zero torque, the joint is left free
  position,  // reference [rad or m] reached by a minimum-jerk trajectory at the reference speed
  position_direct,  // reference [rad or m] tracked directly by the joint PID (streaming)
  velocity,         // reference [rad/s or m/s] (streaming)
  torque,           // reference [N m or N] (streaming)
  pwm,              // duty cycle reference [-1, 1] (streaming)
};

template <>
struct EnumNames<ControlMode> {
  static constexpr std::array names{"IDLE",     "POSITION", "POSITION_DIRECT",
                                    "VELOCITY", "TORQUE",   "PWM"};
};

constexpr const char* to_string(ControlMode mode) { return enum_name(mode); }

// The modes whose reference is followed as it streams in (every one but IDLE
// and POSITION, which plans its own trajectory to a target).
constexpr bool is_streaming(ControlMode mode) {
  return mode == ControlMode::position_direct || mode == ControlMode::velocity ||
         mode == ControlMode::torque || mode == ControlMode::pwm;
}

}  // namespace wbi
