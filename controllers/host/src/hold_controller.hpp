// `hold`, the controller host's own fallback: gravity compensation and joint
// damping about the posture measured when it is activated (PD + gravity,
// pd_gravity.hpp, whose target is that posture). The host owns it: it runs
// whatever controllers a lab brings, and falls back to it on their joints.
//
// Parameters: bandwidth_hz (default 2, gains from M at the held posture, taken
// at each activation), gain_scale, and contacts: the frames a floating-base
// robot stands on, e.g. "l_sole,r_sole" (text; default none). With contacts,
// hold adds the torques that carry the robot's weight on them at each tick's
// posture (G = Sᵀτ + Σ J_cᵀ f, the wrenches that balance the base's rows of
// G with the least Σ |force|² + |moment / 1 cm|²: the feet's forces carry
// the CoM by the lever rule): without them a standing humanoid sags under the
// joint gravity of a floating base, which is the weight hanging from the base.
// Its gains are then those of the robot standing: K_p = ω² × the inertia the
// joints see with the contacts held (an ankle carries the body, not its
// foot), K_d per joint, capped at M_jj,ii / loop_delay_s (default 0.004 s)
// so that a joint stays stable on its own inertia when the feet are not
// held (gains_on_contacts).
#pragma once

#include <array>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <wbi/controllers/controller.hpp>
#include <wbi/controllers/pd_gravity.hpp>

namespace wbi::controllers {

class HoldController final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override;
  std::vector<std::string> signal_names() const override;
  void configure(WholeBodyInterface& robot, const ParameterTable& parameters) override;
  void activate(const RobotState& measured) override;
  bool update(double time_s, double period_s) override;
  void parameters_changed(const ParameterTable& parameters) override;
  const Eigen::VectorXd& command() const override { return command_; }
  std::span<const double> signals() const override { return signals_; }
  std::int64_t signals_stamp_ns() const override { return law_->state().stamp.source_ns; }
  void progress(char* line, std::size_t size) const override;

 private:
  // The joint torques that carry the weight on the contacts at `measured`
  // (offset_); at activation and at every tick, without allocating.
  void weight_on_contacts(const RobotState& measured);
  // With contacts, the law's gains: K_p from the inertia the joints see
  // with the contacts held, K_d per joint within what the loop's delay allows.
  // Needs mass_matrix_ and contact_jacobian_ at the held posture.
  void gains_on_contacts(double bandwidth_hz);

  WholeBodyInterface* robot_ = nullptr;
  std::optional<PdGravity> law_;
  std::size_t bandwidth_index_ = 0, scale_index_ = 0, delay_index_ = 0;
  double bandwidth_hz_ = 2.0, loop_delay_s_ = 0.004;
  Eigen::MatrixXd mass_matrix_;
  Eigen::VectorXd held_, command_;
  std::array<double, 2> signals_{};  // max joint error, 0 (pd_gravity's pair: one plot for both)
  std::vector<int> contacts_;        // frame indices
  Eigen::MatrixXd jacobian_, base_map_;  // 6 × (6 + n); 6 × 6k: G_b = base_map f
  // gains_on_contacts: J_c stacked (6k × (6 + n)); S = [0 I] (n × (6 + n));
  // M⁻¹Sᵀ, M⁻¹J_cᵀ, J_c M⁻¹Sᵀ; A, A⁺ + P M_jj P and P (n × n).
  Eigen::MatrixXd contact_jacobian_, selection_, m_inv_s_, m_inv_jt_, j_m_inv_s_;
  Eigen::MatrixXd mobility_, standing_, locked_;
  Eigen::LDLT<Eigen::MatrixXd> inertia_, operational_;    // of M; of J_c M⁻¹ J_cᵀ
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes_;  // of A
  Eigen::VectorXd gravity_, wrenches_, offset_;           // 6 + n; 6k; n
};

}  // namespace wbi::controllers
