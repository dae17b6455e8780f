// CommandHold: the joint commands of the last write(), held over the steps of
// the control period until the next, and what each joint's actuator applies for
// them (actuator_output(), sensor_actuator_models.hpp). Every engine holds
// commands the same way; nothing allocates after construction.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "wbi/actuation/robot_backend.hpp"
#include "wbi/sim_models/sim_plan.hpp"

namespace wbi::sim_models {

class CommandHold {
 public:
  CommandHold() = default;
  explicit CommandHold(const SimPlan& plan);

  // Holds `commands` (sized for the plan's joints) from now on.
  void hold(const actuation::JointCommands& commands);
  // Every joint IDLE, value 0: what deactivation leaves.
  void release();
  // Joint j's actuator for the held command at joint velocity dq: its torque
  // [N·m], also kept in torque()[j], with the PWM duty that goes with it in pwm()[j].
  double actuate(int j, double dq);

  const Eigen::VectorXd& torque() const { return torque_; }  // [n] of the last actuate()
  const Eigen::VectorXd& pwm() const { return pwm_; }        // [n] of the last actuate()

 private:
  std::vector<actuation::OutputMode> mode_;
  Eigen::VectorXd value_;
  Eigen::VectorXd effort_limit_;
  std::vector<DcMotor> motors_;
  Eigen::VectorXd torque_, pwm_;
};

}  // namespace wbi::sim_models
