#include "hold_controller.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wbi::controllers {

std::vector<ParameterSpec> HoldController::parameters() const {
  return {{.name = "bandwidth_hz",
           .unit = "Hz",
           .help = "gains from the joint inertia at the held posture, taken at activation",
           .default_value = {2.0},
           .min = 1e-3,
           .max = 200.0},
          {.name = "gain_scale",
           .help = "multiplies K_p and K_d",
           .default_value = {1.0},
           .min = 0.0,
           .max = 10.0},
          {.name = "loop_delay_s",
           .unit = "s",
           .help = "with contacts: the loop's delay (a period and the velocity filter's lag); "
                   "each joint's damping at most its own inertia M_jj,ii over it",
           .default_value = {0.004},
           .min = 1e-5,
           .max = 1.0},
          {.name = "contacts",
           .help = "frames it stands on, comma-separated (e.g. l_sole,r_sole)",
           .live = false,
           .text = true}};
}

std::vector<std::string> HoldController::signal_names() const {
  return {"max_joint_error", "reference_to_target"};
}

void HoldController::configure(WholeBodyInterface& robot, const ParameterTable& parameters) {
  robot_ = &robot;
  const int n = robot.dofs();
  law_.emplace(robot);
  mass_matrix_.setZero(n + 6, n + 6);
  held_.setZero(n);
  command_.setZero(n);
  bandwidth_index_ = parameters.index("bandwidth_hz");
  scale_index_ = parameters.index("gain_scale");
  delay_index_ = parameters.index("loop_delay_s");
  parameters_changed(parameters);
  const std::string contacts = parameters.text(parameters.index("contacts"));
  contacts_.clear();
  for (std::size_t start = 0; start < contacts.size();) {
    const std::size_t end = std::min(contacts.find(',', start), contacts.size());
    if (end > start) {
      contacts_.push_back(robot.frame_index(contacts.substr(start, end - start)));
    }
    start = end + 1;
  }
  const auto k = static_cast<Eigen::Index>(contacts_.size());
  jacobian_.setZero(6, n + 6);
  contact_jacobian_.setZero(6 * k, n + 6);
  selection_.setZero(n, n + 6);
  selection_.rightCols(n).setIdentity();
  // Sized once here (a factorisation of the same size then allocates nothing);
  // computed on identities rather than move-assigned from sized temporaries,
  // which GCC 12 at -O1 (the sanitizer build) flags as maybe-uninitialized.
  inertia_.compute(Eigen::MatrixXd::Identity(n + 6, n + 6));
  if (k > 0) {
    operational_.compute(Eigen::MatrixXd::Identity(6 * k, 6 * k));
  }
  modes_.compute(Eigen::MatrixXd::Identity(n, n));
  m_inv_s_.setZero(n + 6, n);
  m_inv_jt_.setZero(n + 6, 6 * k);
  j_m_inv_s_.setZero(6 * k, n);
  mobility_.setZero(n, n);
  standing_.setZero(n, n);
  locked_.setZero(n, n);
  base_map_.setZero(6, 6 * k);
  gravity_.setZero(n + 6);
  wrenches_.setZero(6 * k);
  offset_.setZero(n);
}

void HoldController::weight_on_contacts(const RobotState& measured) {
  offset_.setZero();
  if (contacts_.empty()) {
    return;
  }
  const int n = robot_->dofs();
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  robot_->gravity_forces(measured.q, measured.world_H_base, gravity, gravity_);
  // G_b = Σ J_c,bᵀ f: the base rows. Of the wrenches f = (force, moment) that
  // satisfy them, those of least Σ |force|² + |moment / ℓ|²: with ℓ = 1 cm
  // the forces carry the CoM's offset between the feet (the lever rule) and a
  // foot's moment only what the forces cannot (the CoM ahead of both feet).
  // With ℓ = 1 m (plain least norm) the ankles carried it, 279 N and 55 N
  // measured became 165 N each, and the humanoid fell in 1.5 s.
  constexpr double kMomentLength = 0.01;  // ℓ [m]
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    robot_->jacobian(measured.q, measured.world_H_base, contacts_[c], jacobian_);
    const auto at = 6 * static_cast<Eigen::Index>(c);
    contact_jacobian_.middleRows(at, 6) = jacobian_;
    base_map_.middleCols(at, 6) = jacobian_.leftCols(6).transpose();
    base_map_.middleCols(at + 3, 3) *= kMomentLength;  // columns of (force, moment / ℓ)
  }
  const Eigen::Matrix<double, 6, 6> gram = base_map_ * base_map_.transpose();
  const Eigen::Matrix<double, 6, 1> multipliers = gram.ldlt().solve(gravity_.head<6>());
  wrenches_.noalias() = base_map_.transpose() * multipliers;
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    wrenches_.segment<3>(6 * static_cast<Eigen::Index>(c) + 3) *= kMomentLength;  // moment
  }
  // τ = G_j − Σ J_c,jᵀ f: the joint rows.
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const auto at = 6 * static_cast<Eigen::Index>(c);
    offset_.noalias() -=
        contact_jacobian_.middleRows(at, 6).rightCols(n).transpose() * wrenches_.segment<6>(at);
  }
}

// The hold's gains on a robot that stands on its contacts, held rigid.
//
// Stiffness: the joint block of M is the inertia with the base fixed; standing,
// the base is free and the feet are fixed, and a joint moves what it carries
// (an ankle the whole body, not its foot: 2.73 against 0.0039 kg m² on the
// humanoid). The joint accelerations per joint torque with the contact forces
// eliminated (M ν̇ + h = Sᵀτ + J_cᵀ f with J_c ν̇ = −J̇_c ν, solved for f) are
//   A = S (M⁻¹ − M⁻¹J_cᵀ (J_c M⁻¹ J_cᵀ)⁻¹ J_c M⁻¹) Sᵀ       (n × n, rank n + 6 − 6k)
// and K_p = ω² A⁺ places every motion the closed chain allows at ω. In the
// directions A does not move (squeezing the chain, which only the contacts'
// compliance allows) K_p keeps the joint block of M, as without contacts.
//
// Damping: above the contacts' resonance the feet are not held, and a joint
// sees its own inertia M_jj,ii through the loop's delay h (a period plus the
// velocity filter's lag). m v̇ = −d v(t − h) is stable only while d h / m < π/2:
// K_d is diagonal, d_i = min(2ω (A⁺)_ii, M_jj,ii / h), a margin of π/2.
void HoldController::gains_on_contacts(double bandwidth_hz) {
  if (contacts_.empty()) {
    return;  // from_inertia's: the joint block of M
  }
  const int n = robot_->dofs();
  const auto m_jj = mass_matrix_.bottomRightCorner(n, n);
  inertia_.compute(mass_matrix_);
  m_inv_s_ = inertia_.solve(selection_.transpose());          // M⁻¹ Sᵀ, (6 + n) × n
  m_inv_jt_ = inertia_.solve(contact_jacobian_.transpose());  // M⁻¹ J_cᵀ, (6 + n) × 6k
  operational_.compute(contact_jacobian_ * m_inv_jt_);        // J_c M⁻¹ J_cᵀ
  j_m_inv_s_.noalias() = contact_jacobian_ * m_inv_s_;        // J_c M⁻¹ Sᵀ
  mobility_ = m_inv_s_.bottomRows(n);
  mobility_.noalias() -= j_m_inv_s_.transpose() * operational_.solve(j_m_inv_s_);
  modes_.compute(0.5 * (mobility_ + mobility_.transpose()));
  const Eigen::VectorXd& lambda = modes_.eigenvalues();  // ascending, ≥ 0 but for rounding
  const Eigen::MatrixXd& v = modes_.eigenvectors();
  const double tolerance = 1e-9 * lambda.cwiseAbs().maxCoeff();
  // standing = A⁺ + P M_jj P, P the projector on A's null space.
  standing_.setZero();
  locked_.setZero();
  for (int i = 0; i < n; ++i) {
    if (lambda[i] > tolerance) {
      standing_.noalias() += v.col(i) * (v.col(i).transpose() / lambda[i]);
    } else {
      locked_.noalias() += v.col(i) * v.col(i).transpose();
    }
  }
  standing_.noalias() += locked_ * m_jj * locked_;
  const double omega = 2.0 * M_PI * bandwidth_hz;
  auto& gains = law_->gains();
  gains.kp = omega * omega * standing_;
  gains.kd.setZero();
  for (int i = 0; i < n; ++i) {
    gains.kd(i, i) = std::min(2.0 * omega * standing_(i, i), m_jj(i, i) / loop_delay_s_);
  }
}

void HoldController::parameters_changed(const ParameterTable& parameters) {
  bandwidth_hz_ = parameters.value(bandwidth_index_);  // used at the next activation
  loop_delay_s_ = parameters.value(delay_index_);      // likewise
  law_->set_gain_scale(parameters.value(scale_index_));
}

// Gains from the inertia at the held posture (activate may allocate).
void HoldController::activate(const RobotState& measured) {
  robot_->set_control_mode(ControlMode::torque);
  const int n = robot_->dofs();
  robot_->mass_matrix(measured.q, measured.world_H_base, mass_matrix_);
  law_->gains() = PdGravityGains::from_inertia(mass_matrix_.bottomRightCorner(n, n), bandwidth_hz_);
  weight_on_contacts(measured);
  gains_on_contacts(bandwidth_hz_);
  held_ = measured.q;
  law_->set_reference(held_);
}

bool HoldController::update(double /*time_s*/, double /*period_s*/) {
  law_->compute(ReadMode::latest);
  command_ = law_->torques();
  // The weight carried at this tick's posture: frozen at the held one, the
  // loaded knee of a humanoid handed over with 279 N and 55 N on its feet
  // sank on, its error growing 1.7 times a second.
  weight_on_contacts(law_->state());
  command_ += offset_;
  signals_[0] = law_->max_error();
  return true;
}

void HoldController::progress(char* line, std::size_t size) const {
  std::snprintf(line, size, "max joint error %.4f rad", law_->max_error());
}

std::unique_ptr<Controller> make_hold_controller() { return std::make_unique<HoldController>(); }

}  // namespace wbi::controllers
