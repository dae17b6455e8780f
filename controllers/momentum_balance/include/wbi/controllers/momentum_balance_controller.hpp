// Momentum-based balancing (momentum_balance.hpp) under the controller
// contract. Its CoM reference is an input (reference_input.hpp): `com`, on
// wbi/<robot>/references/<controller>/com, from a planner or the com_sinusoid
// generator (controllers/references). Without points it holds the measured
// CoM; when they stop it decays to the measured CoM (decay_to_state, 0.5 s).
// References are in the state's world frame when the controller started: a
// new estimator's frame (a legged base restarts at x = y = 0) moves them by
// the CoM's jump, so that the robot does not follow the frame.
//
// Parameters (MomentumBalanceParameters's, by the same names):
//   left_sole, right_sole (text), foot_x_min/max, foot_y_min/max, friction,
//   torsional_friction, min_normal_force, posture_bandwidth_hz: at configure;
//   com_kp, com_kd, angular_momentum_kd, torque_weight, wrench_weight,
//   foot_moment_weight, wrench_correction: live.
//   contact_forces planned (default) or estimated: the torques are corrected by
//                  the feet wrenches the state estimates (estimated_contact_forces),
//                  on left_wrench_links / right_wrench_links ('+'-joined; default:
//                  the sole frames), low-passed at wrench_correction_cutoff_hz
//   posture        the postural task's joint reference (default: the posture
//                  measured at configure)
//   settle_s       the CoM error figures count from this long after activation
//                  (the generator's settling)
//   exit_after_s   the run ends (finished()) this long after the first state (0: never)
// Time is the state's source time since the first state it answered, so that
// a lockstep run's figures do not depend on the host's clock.
#pragma once

#include <array>
#include <optional>

#include "wbi/controllers/answered_states.hpp"
#include "wbi/controllers/controller.hpp"
#include "wbi/controllers/momentum_balance.hpp"

namespace wbi::controllers {

class MomentumBalanceController final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override;
  std::vector<std::string> signal_names() const override;
  void configure(WholeBodyInterface& robot, const ParameterTable& parameters) override;
  void activate(const RobotState& measured) override;
  bool update(double time_s, double period_s) override;
  void parameters_changed(const ParameterTable& parameters) override;
  void state_source_changed() override;
  std::vector<ReferenceSpec> references() const override;
  void bind_references(std::span<ReferenceInput* const> inputs) override { com_input_ = inputs[0]; }
  bool finished() const override { return finished_; }
  const Eigen::VectorXd& command() const override { return balance_->torques(); }
  std::span<const double> signals() const override { return signals_; }
  std::int64_t signals_stamp_ns() const override { return answered_.stamp_ns(); }
  void progress(char* line, std::size_t size) const override;
  std::string summary() const override;
  std::string figures_missing() const override;

 private:
  void follow_reference(std::int64_t stamp_ns);
  void publish_signals();

  WholeBodyInterface* robot_ = nullptr;
  std::optional<MomentumBalance> balance_;
  MomentumBalanceParameters tracking_;
  ReferenceInput* com_input_ = nullptr;
  Eigen::Vector3d frame_shift_ = Eigen::Vector3d::Zero();  // new estimators' frames, summed
  double settle_s_ = 0.0, exit_after_s_ = 0.0;
  bool finished_ = false;
  bool new_estimator_ = false;
  bool reference_came_ = false;  // the CoM figures count only from the first reference point
  AnsweredStates answered_;
  double squared_error_ = 0.0, max_error_ = 0.0, squared_force_miss_ = 0.0,
         squared_moment_miss_ = 0.0;
  std::uint64_t samples_ = 0, new_estimators_ = 0;
  std::array<double, 9> signals_{};
  // Indices of com_kp, com_kd, angular_momentum_kd, torque_weight, wrench_weight,
  // foot_moment_weight, wrench_correction: looked up once, at configure.
  std::array<std::size_t, 7> live_{};
};

void register_momentum_balance(ControllerRegistry& registry);

}  // namespace wbi::controllers
