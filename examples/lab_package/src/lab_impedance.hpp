// `lab_impedance`: joint impedance about a posture that a planner sends, with
// gravity compensation, through the whole-body interface only:
//
//   τ = G_j(q) + K (q_ref − q) − D q̇
//
// G_j the joint rows of the model's gravity forces at the measured q, K and D
// diagonal (one stiffness and one damping per joint), q_ref the reference
// input `posture` (wbi/<robot>/references/<controller>/posture) at the
// state's stamp.
//
// Parameters (declared: the host reads them from the deploy file, checks
// them, and `wbi param list lab_impedance --robot ROBOT` shows them):
//   stiffness  K, one per joint [N m/rad]       live: changes while it runs
//   damping    D, one per joint [N m s/rad]     while inactive only
// Reference input:
//   posture    q_ref, 7 values [rad] (the size of an input is fixed when it
//              is declared, before the controller knows its robot: this
//              controller is for the 7-joint arm, and refuses another joint
//              count at configure). Stale (no point for 50 ms): hold_last,
//              the impedance holds the last posture it was sent.
#pragma once

#include <array>
#include <cstdint>

#include <wbi/controllers/controller.hpp>

namespace lab {

class LabImpedance final : public wbi::controllers::Controller {
 public:
  static constexpr int kJoints = 7;  // the posture input's size

  std::vector<wbi::controllers::ParameterSpec> parameters() const override;
  std::vector<wbi::controllers::ReferenceSpec> references() const override;
  std::vector<std::string> signal_names() const override;
  void bind_references(std::span<wbi::controllers::ReferenceInput* const> inputs) override;

  void configure(wbi::WholeBodyInterface& robot,
                 const wbi::controllers::ParameterTable& parameters) override;
  void parameters_changed(const wbi::controllers::ParameterTable& parameters) override;
  void activate(const wbi::RobotState& measured) override;
  bool update(double time_s, double period_s) override;

  const Eigen::VectorXd& command() const override { return tau_; }
  std::span<const double> signals() const override { return signals_; }
  std::int64_t signals_stamp_ns() const override { return state_.stamp.source_ns; }
  void progress(char* line, std::size_t size) const override;
  std::string summary() const override;

 private:
  wbi::WholeBodyInterface* robot_ = nullptr;
  wbi::controllers::ReferenceInput* posture_ = nullptr;
  std::size_t stiffness_index_ = 0, damping_index_ = 0;

  // Sized at configure; update() only writes into them.
  wbi::RobotState state_;
  Eigen::VectorXd k_, d_;  // [n] diagonal stiffness and damping
  Eigen::VectorXd g_;      // [n + 6] gravity forces, base rows first
  Eigen::VectorXd error_;  // [n] q_ref − q
  Eigen::VectorXd tau_;    // [n] the command

  bool answered_ = false;  // a state was answered since activation
  std::uint64_t last_seq_ = 0;
  double max_error_ = 0.0;
  wbi::controllers::ReferenceStatus posture_status_ = wbi::controllers::ReferenceStatus::missing;
  std::array<double, 2> signals_{};  // max joint error, posture fresh (1) or not (0)
};

}  // namespace lab
