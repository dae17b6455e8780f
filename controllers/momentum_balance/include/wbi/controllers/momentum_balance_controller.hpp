// Momentum-based balancing (momentum_balance.hpp) under the controller
// contract, with the balancing demo's CoM sinusoid (com_sinusoid.hpp) as its
// reference.
//
// Parameters (MomentumBalanceParameters's, by the same names):
//   left_sole, right_sole (text), foot_x_min/max, foot_y_min/max, friction,
//   torsional_friction, min_normal_force, posture_bandwidth_hz: at configure;
//   com_kp, com_kd, angular_momentum_kd, torque_weight, wrench_weight,
//   foot_moment_weight: live.
//   posture        the postural task's joint reference (default: the posture
//                  measured at configure)
//   com_amplitude, com_frequency_hz, com_direction (3 numbers), settle_s: the
//                  sinusoid, at configure
//   exit_after_s   the run ends (finished()) this long after the first state (0: never)
// Time is the state's source time since the first state it answered, so that
// a lockstep run's figures do not depend on the host's clock.
#pragma once

#include <array>
#include <optional>

#include "wbi/controllers/com_sinusoid.hpp"
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
  bool finished() const override { return finished_; }
  const Eigen::VectorXd& command() const override { return balance_->torques(); }
  std::span<const double> signals() const override { return signals_; }
  std::int64_t signals_stamp_ns() const override { return stamp_ns_; }
  void progress(char* line, std::size_t size) const override;
  std::string summary() const override;

 private:
  void follow_reference(double t);
  void publish_signals();

  WholeBodyInterface* robot_ = nullptr;
  std::optional<MomentumBalance> balance_;
  MomentumBalanceParameters tracking_;
  ComSinusoid reference_;
  double exit_after_s_ = 0.0;
  bool finished_ = false;
  bool new_estimator_ = false;
  std::int64_t start_ns_ = -1, stamp_ns_ = 0;
  std::uint64_t last_seq_ = 0;
  bool has_seq_ = false;
  double squared_error_ = 0.0, max_error_ = 0.0;
  std::uint64_t samples_ = 0, new_estimators_ = 0;
  std::array<double, 9> signals_{};
  // Indices of com_kp, com_kd, angular_momentum_kd, torque_weight, wrench_weight,
  // foot_moment_weight: looked up once, at configure.
  std::array<std::size_t, 6> live_{};
};

void register_momentum_balance(ControllerRegistry& registry);

}  // namespace wbi::controllers
