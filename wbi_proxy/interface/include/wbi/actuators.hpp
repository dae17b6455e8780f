// The Actuators element: control modes and references of the controlled joints.
#pragma once

#include "wbi/types.hpp"

namespace wbi {

class Actuators {
 public:
  virtual ~Actuators() = default;

  // Switches every controlled joint (or one, by its index in the controller's
  // joint list) to `mode`, atomically in one robot tick. The reference of the
  // new mode starts at the measured position for position modes and at zero
  // for the others, until the next set_control_reference.
  virtual void set_control_mode(ControlMode mode) = 0;
  virtual void set_control_mode(ControlMode mode, int joint) = 0;

  // References in the unit of each joint's mode: all controlled joints
  // (size dofs()), or one joint. Sent to the robot at once.
  virtual void set_control_reference(const ConstVectorRef& reference) = 0;
  virtual void set_control_reference(double reference, int joint) = 0;

  // Gains (kp, ki, kd) and the position-mode reference speed, for every
  // controlled joint (size dofs()) or one joint.
  virtual void set_control_parameter(ControlParameter parameter, const ConstVectorRef& values) = 0;
  virtual void set_control_parameter(ControlParameter parameter, double value, int joint) = 0;
};

}  // namespace wbi
