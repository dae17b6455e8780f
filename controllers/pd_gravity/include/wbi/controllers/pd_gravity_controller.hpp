// PD + gravity (pd_gravity.hpp) under the controller contract. (`hold`, the
// host's fallback, is the same law about the posture measured when it is
// activated: controllers/host/src/hold_controller.hpp.)
//
// pd_gravity's parameters:
//   target        q_d, one per host joint [rad]; hosted on some of the
//                 host's joints, only theirs count                    live
//   bandwidth_hz  gains from the joint block of M(q_d): K_p = ω² M_jj,
//                 K_d = 2ω M_jj, ω = 2π bandwidth (default 5)          at configure
//   kp, kd        diagonal gains instead, one per joint (both or neither)
//   gain_scale    multiplies K_p and K_d (default 1)                  live
//   transition_s  the reference moves from the measured posture (at
//                 activation) or from the last reference (at a change of
//                 target) to the target in this time, minimum jerk
//                 (default 0: a step, as the paper's controller)      live
#pragma once

#include <array>
#include <optional>

#include "wbi/controllers/controller.hpp"
#include "wbi/controllers/pd_gravity.hpp"

namespace wbi::controllers {

class PdGravityController final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override;
  std::vector<std::string> signal_names() const override;
  void configure(WholeBodyInterface& robot, const ParameterTable& parameters) override;
  void activate(const RobotState& measured) override;
  bool update(double time_s, double period_s) override;
  void parameters_changed(const ParameterTable& parameters) override;
  void bind_joints(std::span<const int> joints) override;
  // The law's torques, where it computed them: no copy.
  const Eigen::VectorXd& command() const override { return law_->torques(); }
  std::span<const double> signals() const override { return signals_; }
  std::int64_t signals_stamp_ns() const override { return law_->state().stamp.source_ns; }
  void progress(char* line, std::size_t size) const override;
  std::string summary() const override;

 private:
  // The law's gains K_p = ω² M_jj, K_d = 2ω M_jj from the inertia at `posture`
  // (PdGravityGains::from_inertia; configure only: it allocates).
  void gains_from_inertia(const Eigen::VectorXd& posture, const Transform& world_H_base,
                          double bandwidth_hz);

  // Sizes the law and the buffers for robot.dofs().
  void size_for(WholeBodyInterface& robot);

  WholeBodyInterface* robot_ = nullptr;
  std::optional<PdGravity> law_;
  Eigen::MatrixXd mass_matrix_;
  Eigen::VectorXd from_, goal_, reference_;
  double transition_s_ = 0.0;
  double transition_start_s_ = -1.0;  // < 0: at the next update
  std::array<double, 2> signals_{};   // max joint error, reference's distance to the target
  std::vector<int> joints_;           // the ones it commands: its error figures' (empty: all)

  struct Indices {
    std::size_t target, bandwidth, kp, kd, scale, transition;
  };
  Indices index_{};
};

void register_pd_gravity(ControllerRegistry& registry);

}  // namespace wbi::controllers
