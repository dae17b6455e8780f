// The estimator component's `accelerations: model` input: the joint
// accelerations the model predicts (wbi::estimation::ModelAccelerations) from
// every joint's latest TORQUE command (wbi/<robot>/commands; in lockstep the
// component holds a sample until the commands of the tick before it came:
// README.md, "A tick's inputs"), at the state's base, with the contact links joint_torques:
// force_torque finds loaded held. A joint whose last command is not TORQUE has an unknown torque:
// no model acceleration then. The wrenches estimated on extra links (a push on the chest) do not
// enter: they are noisy when nothing pushes (iCub 3: 9 N RMS on the chest), and with them the legs'
// and torso's q̈ error was 0.53 rad/s² instead of 0.18 (balancing in MuJoCo, frictionless joints).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <wbi/msg/commands.h>
#include <wbi/msg/state.h>
#include <Eigen/Core>
#include <wbi/estimation/model_accelerations.hpp>
#include <wbi/estimation/wrench_estimator.hpp>

namespace wbi::estimator::detail {

class AccelerationsFromModel {
 public:
  // `model` in the robot's joint order (that of the commands' joint indices),
  // with the armature. `wrenches`: the F/T-based estimator whose contact links
  // are held when loaded (its model has the same frames), or null. Outlives this.
  AccelerationsFromModel(model::Model model, estimation::JointLosses losses,
                         const estimation::WrenchEstimator* wrenches);

  // A command of any controller: its TORQUE joints' references are their
  // torques from now on, its other joints' torques unknown. A malformed one
  // (sizes that differ, an index out of range) is skipped: the robot refuses
  // it and reports it on its status. Never allocates.
  void on_command(const wbi::msg::ActuatorCommand& command);

  // The joints' accelerations at q, dq and the base of `state` (pose and
  // velocity written). False, ddq untouched, while a joint has no torque
  // command. Never allocates.
  bool compute(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& dq,
               const wbi::msg::StateEstimate& state, Eigen::VectorXd& ddq);

  // The joints without a torque command, for the one message saying why
  // compute() returned false (allocates).
  std::string joints_without_torque() const;

 private:
  std::unique_ptr<estimation::ModelAccelerations> accelerations_;
  const estimation::WrenchEstimator* wrenches_;
  std::vector<int> contact_hypotheses_;  // the wrench estimator's contact links
  std::vector<char> held_;               // per contact link, this sample
  Eigen::VectorXd q_model_, nu_, tau_;   // tau_: [n_joints] commanded
  std::vector<char> torque_known_;       // per joint
  int known_ = 0;                        // joints with a torque
};

}  // namespace wbi::estimator::detail
