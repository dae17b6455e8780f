// `lab_posture`: the planner's posture (posture_trajectory.hpp) as a planner
// hosted beside `lab_impedance`, chained to its `posture` input: it writes the
// point for each state in the same tick, before the controller's update,
// without DDS (the deploy file: `inputs: {posture: planner}` on the
// controller). The component `lab_posture_planner` sends the same points from
// its own process instead.
//
// Parameters: target (rad, one per joint), sway_amplitude (rad, one per joint;
// default none), start_s, move_s, sway_frequency_hz, sway_periods (as the
// component's). Its time starts at the state it is activated on.
#pragma once

#include <cstdint>

#include <wbi/controllers/controller.hpp>

#include "lab_impedance.hpp"
#include "posture_trajectory.hpp"

namespace lab {

class LabPosture final : public wbi::controllers::Controller {
 public:
  std::vector<wbi::controllers::ParameterSpec> parameters() const override;
  std::vector<wbi::controllers::ReferenceSpec> outputs() const override;
  void bind_outputs(std::span<wbi::controllers::ReferenceOutput* const> outputs) override {
    output_ = outputs[0];
  }
  bool commands_joints() const override { return false; }
  void configure(wbi::WholeBodyInterface& robot,
                 const wbi::controllers::ParameterTable& parameters) override;
  void activate(const wbi::RobotState& measured) override;
  bool update(double time_s, double period_s) override;
  const Eigen::VectorXd& command() const override { return none_; }

 private:
  wbi::WholeBodyInterface* robot_ = nullptr;
  wbi::controllers::ReferenceOutput* output_ = nullptr;
  PostureTrajectory trajectory_;
  wbi::RobotState state_;
  Eigen::VectorXd x_, v_, a_, none_;
  std::int64_t start_ns_ = 0, last_ns_ = -1;
};

}  // namespace lab
