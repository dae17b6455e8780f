// The estimator component's `method: model-kalman` input: the joint
// accelerations the model predicts from what the robot is told to do,
//
//   ν̇ = M(q)⁻¹ (Bτ − h(q, ν) + Σ J_Lᵀ f_L)   (forward dynamics, model/aba.hpp)
//
// with τ the latest TORQUE command of every joint (wbi/<robot>/commands) and
// f_L the external wrenches joint_torques: force_torque estimates from the F/T
// sensors (none on a fixed-base robot without it). Its joint part is fed to
// the estimator (estimation/model_kalman.hpp), which corrects its error with
// the encoders. A joint whose last command is not TORQUE has an unknown
// torque: no model acceleration then (the estimator holds the last one).
#pragma once

#include <span>
#include <string>
#include <vector>

#include <wbi/msg/commands.h>
#include <wbi/msg/state.h>
#include <Eigen/Core>
#include <wbi/model/data.hpp>
#include <wbi/model/model.hpp>

namespace wbi::estimator::detail {

class AccelerationsFromModel {
 public:
  // `model` in the robot's joint order (that of the commands' joint indices).
  explicit AccelerationsFromModel(model::Model model);

  // A command of any controller: its TORQUE joints' references are their
  // torques from now on, its other joints' torques unknown. Indices out of
  // range and mismatched sizes are ignored (counted). Never allocates.
  void on_command(const wbi::msg::ActuatorCommand& command);

  // The joints' accelerations at q, dq and the base of `state` (pose and
  // velocity written), with `wrenches` at the model's frames. False, ddq
  // untouched, while a joint has no torque command. Never allocates.
  bool compute(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
               const wbi::msg::StateEstimate& state,
               std::span<const model::ExternalWrench> wrenches, Eigen::VectorXd& ddq);

  // The joints without a torque command, for the one message saying why
  // compute() returned false (allocates).
  std::string joints_without_torque() const;
  std::uint64_t malformed_commands() const { return malformed_commands_; }
  const model::Model& model() const { return model_; }

 private:
  model::Model model_;
  model::Data data_;
  Eigen::VectorXd q_model_, nu_, tau_;  // tau_: [nv], the base's entries 0
  std::vector<char> torque_known_;      // per joint
  int known_ = 0;                       // joints with a torque
  std::uint64_t malformed_commands_ = 0;
};

}  // namespace wbi::estimator::detail
