// Whole-body walking (walking_qp.hpp) under the controller contract. Its
// references are one input, `walk` (walking_plan.hpp's 16 values: DCM, CoM,
// both soles, contact weights), from the walking_planner chained in the same
// host or from a planner's topic. Without points it stands where it is.
//
// Parameters: WalkingQpParameters's by the same names (left_sole,
// right_sole, torso, foot_x_min/max, foot_y_min/max, friction,
// torsional_friction, min_normal_force, max_normal_force, posture_bandwidth_hz
// at configure; the gains and weights live), posture (default: measured at
// configure), exit_after_s (0: never), fall_height (the base below this
// height above the lower sole is a fall: the run ends and fails).
//
// Figures (summary(), from the state the controller reads): steps, average
// speed over the walk, step length and duration, DCM and CoM tracking rms,
// the largest slip of a stance foot per step, the largest touch-down
// position error, the stance feet's smallest planned normal force, falls.
#pragma once

#include <array>
#include <optional>

#include "wbi/controllers/answered_states.hpp"
#include "wbi/controllers/controller.hpp"
#include "wbi/controllers/walking_figures.hpp"
#include "wbi/controllers/walking_qp.hpp"

namespace wbi::controllers::walking {

class WalkingController final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override;
  std::vector<std::string> signal_names() const override;
  std::vector<ReferenceSpec> references() const override;
  void bind_references(std::span<ReferenceInput* const> inputs) override { walk_ = inputs[0]; }
  void configure(WholeBodyInterface& robot, const ParameterTable& parameters) override;
  void activate(const RobotState& measured) override;
  bool update(double time_s, double period_s) override;
  void parameters_changed(const ParameterTable& parameters) override;
  bool finished() const override { return finished_; }
  const Eigen::VectorXd& command() const override { return qp_->torques(); }
  std::span<const double> signals() const override { return signals_; }
  std::int64_t signals_stamp_ns() const override { return answered_.stamp_ns(); }
  void progress(char* line, std::size_t size) const override;
  std::string summary() const override;
  std::string figures_missing() const override;

 private:
  void read_targets(std::int64_t stamp_ns);
  void publish_signals();

  std::optional<WalkingQp> qp_;
  WalkingQpParameters configured_;
  ReferenceInput* walk_ = nullptr;
  WalkingReference reference_;
  WalkingTargets targets_, standing_;
  WalkingFigures figures_;
  double exit_after_s_ = 0.0, fall_height_ = 0.0, speed_distance_ = 1.0;
  bool finished_ = false;
  AnsweredStates answered_;
  std::array<double, 12> signals_{};
  std::vector<std::size_t> live_;  // indices of the live gains and weights, at configure
};

void register_walking_controller(ControllerRegistry& registry);

}  // namespace wbi::controllers::walking
