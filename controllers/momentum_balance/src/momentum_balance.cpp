#include "wbi/controllers/momentum_balance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "wbi/controllers/foot_contact.hpp"

namespace wbi::controllers {

namespace {

constexpr int kContacts = 2;
constexpr int kWrenches = 6 * kContacts;
constexpr int kRowsPerFoot = kFootConstraintRows;

void require(bool ok, const std::string& what) {
  if (!ok) {
    throw Error("momentum balance: " + what);
  }
}

}  // namespace

void MomentumBalance::set_tracking(const MomentumBalanceParameters& parameters) {
  const auto& p = parameters;
  require(p.com_kp >= 0.0 && p.com_kd >= 0.0 && p.angular_momentum_kd >= 0.0, "gains must be >= 0");
  require(p.torque_weight >= 0.0 && p.wrench_weight > 0.0 && p.foot_moment_weight >= 0.0,
          "torque_weight and foot_moment_weight must be >= 0, wrench_weight > 0");
  require(p.wrench_correction >= 0.0 && p.wrench_correction <= 1.0,
          "wrench_correction must be in [0, 1]");
  p_.com_kp = p.com_kp;
  p_.com_kd = p.com_kd;
  p_.angular_momentum_kd = p.angular_momentum_kd;
  p_.torque_weight = p.torque_weight;
  p_.wrench_weight = p.wrench_weight;
  p_.foot_moment_weight = p.foot_moment_weight;
  p_.wrench_correction = p.wrench_correction;
}

MomentumBalance::MomentumBalance(WholeBodyInterface& robot, MomentumBalanceParameters parameters,
                                 Eigen::VectorXd q_posture)
    : robot_(robot),
      p_(std::move(parameters)),
      n_(robot.dofs()),
      left_(robot.frame_index(p_.left_sole)),
      right_(robot.frame_index(p_.right_sole)),
      q_posture_(std::move(q_posture)),
      mass_llt_(6 + n_),
      gram_llt_(kWrenches),
      qp_(kWrenches, 0, kContacts * kRowsPerFoot) {
  require(q_posture_.size() == n_, "q_posture has size " + std::to_string(q_posture_.size()) +
                                       ", the controller has " + std::to_string(n_) + " joints");
  require(p_.friction > 0.0, "friction must be > 0");
  require(p_.torsional_friction >= 0.0, "torsional_friction must be >= 0");
  require(p_.foot_x_min < 0.0 && p_.foot_x_max > 0.0 && p_.foot_y_min < 0.0 && p_.foot_y_max > 0.0,
          "the foot rectangle must contain the sole origin (x_min < 0 < x_max, y_min < 0 < y_max)");
  require(p_.min_normal_force >= 0.0, "min_normal_force must be >= 0");
  require(p_.posture_bandwidth_hz >= 0.0, "gains must be >= 0");
  require(p_.wrench_correction_cutoff_hz > 0.0, "wrench_correction_cutoff_hz must be > 0");
  set_tracking(p_);

  const int N = 6 + n_;
  state_ = RobotState(n_);
  M_.setZero(N, N);
  h_.setZero(N);
  Jc_.setZero(kWrenches, N);
  dj_nu_.setZero(kWrenches);
  Minv_Jct_.setZero(N, kWrenches);
  Lambda_.setZero(kWrenches, n_);
  Lambda_pinv_.setZero(n_, kWrenches);
  gram_solve_.setZero(kWrenches, n_);
  gram_.setZero(kWrenches, kWrenches);
  null_.setZero(n_, n_);
  tau_0_.setZero(n_);
  tau_c_.setZero(n_);
  tau_.setZero(n_);
  T_.setZero(n_, kWrenches);
  qp_H_.setZero(kWrenches, kWrenches);
  qp_g_.setZero(kWrenches);
  qp_A_eq_.setZero(0, kWrenches);
  qp_b_eq_.setZero(0);
  qp_C_.setZero(kContacts * kRowsPerFoot, kWrenches);
  qp_d_.setZero(kContacts * kRowsPerFoot);
  for (auto& r : sole_rotation_) {
    r.setIdentity();
  }
  for (auto& x : sole_position_) {
    x.setZero();
  }

  // Postural PD from the joints' inertia at the reference: the same bandwidth for all.
  robot_.mass_matrix(q_posture_, Transform::Identity(), M_);
  mass_ = M_(0, 0);
  const double omega = 2.0 * M_PI * p_.posture_bandwidth_hz;
  posture_kp_ = omega * omega * M_.diagonal().tail(n_);
  posture_kd_ = 2.0 * omega * M_.diagonal().tail(n_);
  joint_inertia_ = M_.diagonal().tail(n_);

  build_constraints();
  if (p_.estimated_contact_forces) {
    resolve_wrench_links();
  }
}

// Each foot's links among the state's external wrenches; one error naming every
// link the state does not estimate.
void MomentumBalance::resolve_wrench_links() {
  const IdList& estimated = robot_.external_wrench_links();
  std::string missing;
  const std::vector<std::string>* lists[kContacts] = {&p_.left_wrench_links,
                                                      &p_.right_wrench_links};
  const std::string* soles[kContacts] = {&p_.left_sole, &p_.right_sole};
  for (int foot = 0; foot < kContacts; ++foot) {
    std::vector<std::string> links = *lists[foot];
    if (links.empty()) {
      links = {*soles[foot]};
    }
    for (const auto& link : links) {
      const auto at = std::find(estimated.begin(), estimated.end(), link);
      if (at == estimated.end()) {
        missing += (missing.empty() ? "" : ", ") + link;
        continue;
      }
      wrench_links_.push_back(
          {foot, static_cast<int>(at - estimated.begin()), robot_.frame_index(link)});
    }
  }
  if (!missing.empty()) {
    std::string known;
    for (const auto& link : estimated) {
      known += (known.empty() ? "" : ", ") + link;
    }
    throw Error("momentum balance: estimated contact forces need the state's external wrench on " +
                missing + "; the state estimates it on [" + known +
                "] (set left_wrench_links / right_wrench_links, or run the estimator with "
                "joint_torques: force_torque and these contact_links)");
  }
}

// Per foot, on the wrench (f, τ) in the sole frame, rows · w ≥ 0 (the first ≥ f_min):
// unilateral; inscribed friction pyramid; CoP in the rectangle; torsional friction.
void MomentumBalance::build_constraints() {
  foot_constraints_ = foot_wrench_constraints({.x_min = p_.foot_x_min,
                                               .x_max = p_.foot_x_max,
                                               .y_min = p_.foot_y_min,
                                               .y_max = p_.foot_y_max,
                                               .friction = p_.friction,
                                               .torsional_friction = p_.torsional_friction});
  qp_d_.setZero();
  for (int foot = 0; foot < kContacts; ++foot) {
    qp_d_[foot * kRowsPerFoot] = p_.min_normal_force;
  }
}

void MomentumBalance::start() {
  robot_.set_control_mode(ControlMode::torque);
  // The wrench correction starts anew: d̂ from an earlier activation is stale.
  corrected_stamp_ns_ = -1;
  wrench_disturbance_.setZero();
  wrench_miss_.setZero();
  wrench_correction_.setZero();
}

void MomentumBalance::set_com_reference(const Eigen::Vector3d& position,
                                        const Eigen::Vector3d& velocity,
                                        const Eigen::Vector3d& acceleration) {
  com_desired_ = position;
  com_velocity_desired_ = velocity;
  com_acceleration_desired_ = acceleration;
  com_reference_set_ = true;
}

Stamp MomentumBalance::read_state(ReadMode mode) {
  const Stamp stamp = robot_.state().read_robot_state(state_, mode);
  last_seq_ = stamp.seq;
  stamp_ns_ = stamp.source_ns;
  return stamp;
}

// τ(f) = τ_c − T f from  M ν̇ + h = Bτ + Jcᵀ f,  Jc ν̇ + J̇ν = 0  (both feet fixed):
//   Λ τ = Jc M⁻¹ (h − Jcᵀ f) − J̇ν,   Λ = Jc M⁻¹ B,
//   τ = Λ† (Jc M⁻¹ (h − Jcᵀ f) − J̇ν) + N_Λ τ₀,   τ₀ = h_j − J_jᵀ f + u₀,
// u₀ the postural PD, N_Λ = I − Λ†Λ the null space of the contact constraints,
// Λ† the inverse of Λ weighted by the joints' inertia at the posture.
void MomentumBalance::compute_torque_map() {
  mass_llt_.compute(M_);
  Minv_Jct_ = Jc_.transpose();
  mass_llt_.solveInPlace(Minv_Jct_);
  Lambda_ = Minv_Jct_.bottomRows(n_).transpose();
  Jc_Minv_Jct_.noalias() = Jc_ * Minv_Jct_;
  constraint_bias_.noalias() = Minv_Jct_.transpose() * h_;
  constraint_bias_ -= dj_nu_;

  // Λ† = Λᵀ (Λ Λᵀ)⁻¹, slightly damped against a near-singular leg.
  // Λ† = W⁻¹Λᵀ (Λ W⁻¹ Λᵀ)⁻¹, W⁻¹ = diag(M_jj): of the torques that keep the
  // feet still, the one of least Σ τ_j² / M_jj, slightly damped against a
  // near-singular leg. Unweighted (least Σ τ_j²), a light joint is a cheap place
  // for torque: iCub 3's arms swung by ±1 rad and a hand hit its limit.
  gram_solve_.noalias() = Lambda_ * joint_inertia_.asDiagonal();
  gram_.noalias() = gram_solve_ * Lambda_.transpose();
  gram_.diagonal().array() += 1e-9;
  gram_llt_.compute(gram_);
  gram_llt_.solveInPlace(gram_solve_);
  Lambda_pinv_ = gram_solve_.transpose();
  null_.noalias() = -Lambda_pinv_ * Lambda_;
  null_.diagonal().array() += 1.0;

  tau_0_ = h_.tail(n_) - posture_kp_.cwiseProduct(state_.q - q_posture_) -
           posture_kd_.cwiseProduct(state_.dq);
  tau_c_.noalias() = Lambda_pinv_ * constraint_bias_;
  tau_c_.noalias() += null_ * tau_0_;
  T_.noalias() = Lambda_pinv_ * Jc_Minv_Jct_;
  T_.noalias() += null_ * Jc_.rightCols(n_).transpose();
}

// A: the feet wrenches' net wrench about the CoM, Ḣ = A f + m g.
void MomentumBalance::compute_momentum_map() {
  for (int foot = 0; foot < kContacts; ++foot) {
    const Eigen::Vector3d arm = sole_position_[foot] - com_;
    A_.block<3, 3>(0, 6 * foot).setIdentity();
    A_.block<3, 3>(0, 6 * foot + 3).setZero();
    A_.block<3, 3>(3, 6 * foot) = skew(arm);
    A_.block<3, 3>(3, 6 * foot + 3).setIdentity();
  }
}

// min ½‖A f − (Ḣ* − m g)‖² + ½ w_τ ‖τ_c − T f‖² + ½ w_f ‖f‖²  s.t. the feet constraints.
void MomentumBalance::solve_wrenches() {
  for (int foot = 0; foot < kContacts; ++foot) {
    // World-axes wrench → sole frame: blockdiag(Rᵀ, Rᵀ).
    const Eigen::Matrix3d Rt = sole_rotation_[foot].transpose();
    qp_C_.block<kRowsPerFoot, 3>(kRowsPerFoot * foot, 6 * foot).noalias() =
        foot_constraints_.leftCols<3>() * Rt;
    qp_C_.block<kRowsPerFoot, 3>(kRowsPerFoot * foot, 6 * foot + 3).noalias() =
        foot_constraints_.rightCols<3>() * Rt;
  }
  Eigen::Matrix<double, 6, 1> target = momentum_rate_desired_;
  target.head<3>() -= mass_ * p_.gravity;
  qp_H_.noalias() = A_.transpose() * A_;
  qp_H_.noalias() += p_.torque_weight * T_.transpose() * T_;
  qp_H_.diagonal().array() += p_.wrench_weight;
  for (int foot = 0; foot < kContacts; ++foot) {
    qp_H_.diagonal().segment<3>(6 * foot + 3).array() += p_.foot_moment_weight;
  }
  qp_g_.noalias() = -A_.transpose() * target;
  qp_g_.noalias() -= p_.torque_weight * T_.transpose() * tau_c_;
  if (qp_.solve(qp_H_, qp_g_, qp_A_eq_, qp_b_eq_, qp_C_, qp_d_) == qp::Status::optimal) {
    wrench_ = qp_.solution();
  } else {
    ++qp_failures_;  // keep the last feasible wrenches
  }
}

// f̂ per foot: Σ over its links of (f, τ + (p_link − p_sole) × f), world axes.
void MomentumBalance::read_estimated_wrenches() {
  wrench_estimated_.setZero();
  for (const WrenchLink& link : wrench_links_) {
    robot_.state().read_estimate(EstimateKind::external_wrench, link.estimate, link_wrench_);
    robot_.frame_pose(state_.q, state_.world_H_base, link.frame, world_H_link_);
    const Eigen::Vector3d arm = world_H_link_.topRightCorner<3, 1>() - sole_position_[link.foot];
    const Eigen::Vector3d force = link_wrench_.head<3>();
    wrench_estimated_.segment<3>(6 * link.foot) += force;
    wrench_estimated_.segment<3>(6 * link.foot + 3) += link_wrench_.tail<3>() + arm.cross(force);
  }
}

// d̂ ← d̂ + α (f̂ − f_cmd − d̂), f_cmd the wrenches the last torques were for,
// α = 1 − exp(−2π f_c Δt) over the state's time since the last update (none at
// the first tick after start(): no torques were sent for it); then
// τ_c += k T A⁺A d̂, so that the QP's torque cost sees the torques sent.
void MomentumBalance::correct_for_wrench_disturbance() {
  if (corrected_stamp_ns_ >= 0 && stamp_ns_ > corrected_stamp_ns_) {
    const double dt = std::min(1e-9 * static_cast<double>(stamp_ns_ - corrected_stamp_ns_), 0.1);
    const double alpha = 1.0 - std::exp(-2.0 * M_PI * p_.wrench_correction_cutoff_hz * dt);
    wrench_disturbance_ += alpha * (wrench_estimated_ - wrench_commanded_ - wrench_disturbance_);
    wrench_miss_ += alpha * (wrench_estimated_ - wrench_planned_ - wrench_miss_);
  }
  if (corrected_stamp_ns_ < 0 || stamp_ns_ > corrected_stamp_ns_) {
    corrected_stamp_ns_ = stamp_ns_;
  }
  // Only d̂'s net wrench, spread over the feet by least norm (A⁺ A d̂): the feet's
  // internal forces are left to the QP.
  const Eigen::Matrix<double, 6, 6> gram = A_ * A_.transpose();
  const Eigen::Matrix<double, 6, 1> net = A_ * wrench_disturbance_;
  wrench_correction_.noalias() = A_.transpose() * gram.llt().solve(net);
  tau_c_.noalias() += p_.wrench_correction * T_ * wrench_correction_;
}

Eigen::Vector3d MomentumBalance::com_of_state() {
  Eigen::Vector3d c;
  robot_.com(state_.q, state_.world_H_base, c);
  return c;
}

Eigen::Vector3d MomentumBalance::feet_center_of_state() {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const int sole : {left_, right_}) {
    robot_.frame_pose(state_.q, state_.world_H_base, sole, world_H_sole_);
    sum += world_H_sole_.topRightCorner<3, 1>();
  }
  return 0.5 * sum;
}

void MomentumBalance::update(ReadMode mode) {
  read_state(mode);
  control();
}

void MomentumBalance::control() {
  compute();
  robot_.set_control_reference(tau_);
}

void MomentumBalance::compute() {
  robot_.mass_matrix(state_.q, state_.world_H_base, M_);
  robot_.bias_forces(state_.q, state_.world_H_base, state_.dq, state_.base_velocity, p_.gravity,
                     h_);
  const int soles[kContacts] = {left_, right_};
  for (int foot = 0; foot < kContacts; ++foot) {
    robot_.jacobian(state_.q, state_.world_H_base, soles[foot], Jc_.middleRows(6 * foot, 6));
    robot_.dj_nu(state_.q, state_.world_H_base, state_.dq, state_.base_velocity, soles[foot],
                 dj_nu_.segment(6 * foot, 6));
    robot_.frame_pose(state_.q, state_.world_H_base, soles[foot], world_H_sole_);
    sole_position_[foot] = world_H_sole_.topRightCorner<3, 1>();
    sole_rotation_[foot] = world_H_sole_.topLeftCorner<3, 3>();
  }
  robot_.com(state_.q, state_.world_H_base, com_);
  robot_.centroidal_momentum(state_.q, state_.world_H_base, state_.dq, state_.base_velocity,
                             momentum_);
  com_velocity_ = momentum_.head<3>() / mass_;
  if (!com_reference_set_) {
    set_com_reference(com_, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  }

  // Desired momentum rate: CoM PD with feed-forward, angular momentum damping.
  momentum_rate_desired_.head<3>() =
      mass_ * (com_acceleration_desired_ - p_.com_kp * (com_ - com_desired_) -
               p_.com_kd * (com_velocity_ - com_velocity_desired_));
  momentum_rate_desired_.tail<3>() = -p_.angular_momentum_kd * momentum_.tail<3>();

  compute_torque_map();
  compute_momentum_map();
  if (p_.estimated_contact_forces) {
    read_estimated_wrenches();
    correct_for_wrench_disturbance();
  }
  solve_wrenches();
  tau_ = tau_c_;
  tau_.noalias() -= T_ * wrench_;
  wrench_planned_ = wrench_;
  wrench_commanded_ = wrench_ - p_.wrench_correction * wrench_correction_;
}

}  // namespace wbi::controllers
