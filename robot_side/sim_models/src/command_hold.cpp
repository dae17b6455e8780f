#include "wbi/sim_models/command_hold.hpp"

namespace wbi::sim_models {

CommandHold::CommandHold(const SimPlan& plan)
    : mode_(static_cast<std::size_t>(plan.n_joints), actuation::OutputMode::kIdle),
      value_(Eigen::VectorXd::Zero(plan.n_joints)),
      effort_limit_(plan.effort_limit),
      motors_(plan.motors),
      torque_(Eigen::VectorXd::Zero(plan.n_joints)),
      pwm_(Eigen::VectorXd::Zero(plan.n_joints)) {}

void CommandHold::hold(const actuation::JointCommands& commands) {
  for (std::size_t j = 0; j < mode_.size(); ++j) {
    mode_[j] = commands.mode[j];
  }
  value_ = commands.value;
}

void CommandHold::release() {
  mode_.assign(mode_.size(), actuation::OutputMode::kIdle);
  value_.setZero();
}

double CommandHold::actuate(int j, double dq) {
  const auto js = static_cast<std::size_t>(j);
  const ActuatorOutput out =
      actuator_output(mode_[js], value_[j], dq, motors_[js], effort_limit_[j]);
  torque_[j] = out.torque;
  pwm_[j] = out.pwm;
  return out.torque;
}

}  // namespace wbi::sim_models
