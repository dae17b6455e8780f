#include "wbi/controllers/walking_qp.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace wbi::controllers::walking {

namespace {

constexpr int kEqualities = 6 + 12;  // floating base; per foot, contact or no wrench
constexpr int kRowsPerFoot = kFootConstraintRows + 1;  // and f_z ≤ w f_max

void require(bool ok, const std::string& what) {
  if (!ok) {
    throw Error("walking controller: " + what);
  }
}

double mean_yaw(double a, double b) {
  return std::atan2(std::sin(a) + std::sin(b), std::cos(a) + std::cos(b));
}

// The rotation vector of R (world axes when R = R_target R_measuredᵀ).
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace

void WalkingTargets::read(const WalkingReference& r) {
  dcm = r.position.segment<3>(0);
  dcm_velocity = r.velocity.segment<3>(0);
  com = r.position.segment<3>(3);
  com_velocity = r.velocity.segment<3>(3);
  com_acceleration = r.acceleration.segment<3>(3);
  for (int f = 0; f < 2; ++f) {
    const int at = 6 + 4 * f;
    feet[f].position = r.position.segment<3>(at);
    feet[f].yaw = r.position[at + 3];
    feet_velocity[f] = r.velocity.segment<4>(at);
    feet_acceleration[f] = r.acceleration.segment<4>(at);
    contact_weight[f] = std::clamp(r.position[14 + f], 0.0, 1.0);
  }
}

void WalkingQp::set_gains(const WalkingQpParameters& g) {
  require(g.dcm_gain >= 0.0 && g.com_height_kp >= 0.0 && g.com_height_kd >= 0.0 &&
              g.angular_momentum_kd >= 0.0 && g.swing_kp >= 0.0 && g.swing_kd >= 0.0 &&
              g.torso_kp >= 0.0 && g.torso_kd >= 0.0 && g.posture_bandwidth_hz >= 0.0,
          "gains must be >= 0");
  require(g.momentum_weight > 0.0 && g.swing_weight >= 0.0 && g.torso_weight >= 0.0 &&
              g.posture_weight >= 0.0 && g.angular_momentum_weight >= 0.0 &&
              g.leg_posture_weight >= 0.0 && g.torque_weight >= 0.0 &&
              g.acceleration_weight > 0.0 && g.wrench_weight > 0.0 && g.foot_moment_weight >= 0.0,
          "weights must be >= 0 (momentum, acceleration and wrench weights > 0)");
  p_.dcm_gain = g.dcm_gain;
  p_.com_height_kp = g.com_height_kp;
  p_.com_height_kd = g.com_height_kd;
  p_.angular_momentum_kd = g.angular_momentum_kd;
  p_.swing_kp = g.swing_kp;
  p_.swing_kd = g.swing_kd;
  p_.torso_kp = g.torso_kp;
  p_.torso_kd = g.torso_kd;
  p_.momentum_weight = g.momentum_weight;
  p_.swing_weight = g.swing_weight;
  p_.torso_weight = g.torso_weight;
  p_.posture_weight = g.posture_weight;
  p_.angular_momentum_weight = g.angular_momentum_weight;
  p_.leg_posture_weight = g.leg_posture_weight;
  p_.torque_weight = g.torque_weight;
  p_.acceleration_weight = g.acceleration_weight;
  p_.wrench_weight = g.wrench_weight;
  p_.foot_moment_weight = g.foot_moment_weight;
  p_.step_adjustment_gain = g.step_adjustment_gain;
  p_.step_adjustment_dead_band = g.step_adjustment_dead_band;
  p_.max_step_adjustment = g.max_step_adjustment;
}

WalkingQp::WalkingQp(WholeBodyInterface& robot, WalkingQpParameters parameters,
                     Eigen::VectorXd posture)
    : robot_(robot),
      p_(std::move(parameters)),
      n_(robot.dofs()),
      N_(6 + n_),
      nx_(N_ + 12),
      sole_{robot.frame_index(p_.left_sole), robot.frame_index(p_.right_sole)},
      torso_(robot.frame_index(p_.torso)),
      posture_(std::move(posture)),
      qp_(nx_, kEqualities, 2 * kRowsPerFoot + 2 * n_) {
  require(posture_.size() == n_, "posture has " + std::to_string(posture_.size()) +
                                     " values, the controller has " + std::to_string(n_) +
                                     " joints");
  require(p_.support.contains_origin(),
          "the foot rectangle must contain the sole origin (x_min < 0 < x_max, y_min < 0 < y_max)");
  require(p_.support.friction > 0.0 && p_.support.torsional_friction >= 0.0,
          "friction must be > 0 and torsional_friction >= 0");
  require(p_.min_normal_force >= 0.0 && p_.max_normal_force > 0.0,
          "min_normal_force must be >= 0, max_normal_force > 0");
  set_gains(p_);
  require(p_.gravity.z() < 0.0, "gravity must point down (its z < 0)");

  state_ = RobotState(n_);
  M_.setZero(N_, N_);
  h_.setZero(N_);
  nu_.setZero(N_);
  Jfeet_.setZero(12, N_);
  Jtorso_.setZero(6, N_);
  dj_nu_feet_.setZero();
  dj_nu_torso_.setZero();
  momentum_.setZero();
  momentum_rate_.setZero();
  for (auto& r : foot_rotation_) {
    r.setIdentity();
  }
  for (auto& v : foot_velocity_) {
    v.setZero();
  }
  H_.setZero(nx_, nx_);
  g_.setZero(nx_);
  A_eq_.setZero(kEqualities, nx_);
  b_eq_.setZero(kEqualities);
  C_.setZero(2 * kRowsPerFoot + 2 * n_, nx_);
  d_.setZero(2 * kRowsPerFoot + 2 * n_);
  effort_.resize(n_);
  for (int j = 0; j < n_; ++j) {
    // No limit in the URDF: a bound never reached keeps the rows' count fixed.
    effort_[j] = std::min(robot.joint_limits(j).effort_max, 1e6);
  }
  torque_map_.setZero(n_, nx_);
  task_b_.setZero(n_);
  tau_.setZero(n_);
  foot_rows_ = foot_wrench_constraints(p_.support);

  robot_.mass_matrix(posture_, Transform::Identity(), M_);
  mass_ = M_(0, 0);
  // A leg joint moves a sole: its column in a sole's Jacobian is not zero.
  leg_joint_.assign(n_, false);
  for (int f = 0; f < 2; ++f) {
    robot_.jacobian(posture_, Transform::Identity(), sole_[f], Jfeet_.middleRows(6 * f, 6));
  }
  for (int j = 0; j < n_; ++j) {
    leg_joint_[j] = Jfeet_.col(6 + j).norm() > 1e-9;
  }
  const double omega = 2.0 * M_PI * p_.posture_bandwidth_hz;
  posture_kp_ = omega * omega;
  posture_kd_ = 2.0 * omega;
}

void WalkingQp::start(const RobotState& measured) {
  robot_.set_control_mode(ControlMode::torque);
  double yaw[2];
  for (int f = 0; f < 2; ++f) {
    robot_.frame_pose(measured.q, measured.world_H_base, sole_[f], pose_);
    yaw[f] = FootPose::of(pose_).yaw;
  }
  robot_.frame_pose(measured.q, measured.world_H_base, torso_, pose_);
  torso_offset_ = Eigen::AngleAxisd(mean_yaw(yaw[0], yaw[1]), Eigen::Vector3d::UnitZ())
                      .toRotationMatrix()
                      .transpose() *
                  pose_.topLeftCorner<3, 3>();
}

Stamp WalkingQp::read_state(ReadMode mode) { return robot_.state().read_robot_state(state_, mode); }

void WalkingQp::evaluate_model() {
  const auto& s = state_;
  nu_.head<6>() = s.base_velocity;
  nu_.tail(n_) = s.dq;
  robot_.mass_matrix(s.q, s.world_H_base, M_);
  robot_.bias_forces(s.q, s.world_H_base, s.dq, s.base_velocity, p_.gravity, h_);
  for (int f = 0; f < 2; ++f) {
    robot_.jacobian(s.q, s.world_H_base, sole_[f], Jfeet_.middleRows(6 * f, 6));
    robot_.dj_nu(s.q, s.world_H_base, s.dq, s.base_velocity, sole_[f],
                 dj_nu_feet_.segment<6>(6 * f));
    robot_.frame_pose(s.q, s.world_H_base, sole_[f], pose_);
    foot_[f] = FootPose::of(pose_);
    foot_rotation_[f] = pose_.topLeftCorner<3, 3>();
    foot_velocity_[f].noalias() = Jfeet_.middleRows(6 * f, 6) * nu_;
  }
  robot_.jacobian(s.q, s.world_H_base, torso_, Jtorso_);
  robot_.dj_nu(s.q, s.world_H_base, s.dq, s.base_velocity, torso_, dj_nu_torso_);
  robot_.frame_pose(s.q, s.world_H_base, torso_, pose_);
  torso_rotation_ = pose_.topLeftCorner<3, 3>();
  robot_.com(s.q, s.world_H_base, com_);
  robot_.centroidal_momentum(s.q, s.world_H_base, s.dq, s.base_velocity, momentum_);
  com_velocity_ = momentum_.head<3>() / mass_;
}

// Only the soles and the CoM: the input asks for this on every tick that has
// no plan point, and compute() evaluates the whole model right after.
void WalkingQp::standing_targets(WalkingTargets& t) {
  const auto& s = state_;
  robot_.com(s.q, s.world_H_base, t.com);
  t.dcm = t.com;
  t.dcm_velocity.setZero();
  t.com_velocity.setZero();
  t.com_acceleration.setZero();
  for (int f = 0; f < 2; ++f) {
    robot_.frame_pose(s.q, s.world_H_base, sole_[f], pose_);
    t.feet[f] = FootPose::of(pose_);
    t.feet_velocity[f].setZero();
    t.feet_acceleration[f].setZero();
    t.contact_weight[f] = 1.0;
  }
}

// Ḣ*: the DCM law horizontally, a PD on the planned CoM height, the angular momentum damped.
void WalkingQp::momentum_rate_target(const WalkingTargets& t) {
  const double g = -p_.gravity.z();
  const double ground = std::min(t.feet[0].position.z(), t.feet[1].position.z());
  const double height = std::max(t.dcm.z() - ground, 0.05);
  const double omega = std::sqrt(g / height);
  dcm_ = com_ + com_velocity_ / omega;
  const Eigen::Vector3d vrp =
      t.dcm - t.dcm_velocity / omega + (1.0 + p_.dcm_gain / omega) * (dcm_ - t.dcm);
  Eigen::Vector3d acceleration;
  acceleration.head<2>() = omega * omega * (com_ - vrp).head<2>();
  acceleration.z() = t.com_acceleration.z() + p_.com_height_kp * (t.com.z() - com_.z()) +
                     p_.com_height_kd * (t.com_velocity.z() - com_velocity_.z());
  momentum_rate_.head<3>() = mass_ * acceleration;
  // Step adjustment: a swinging foot lands off its plan by the DCM's error
  // beyond a dead band, times a gain (a push: the next step catches the DCM).
  step_offset_.setZero();
  const Eigen::Vector2d error = (dcm_ - t.dcm).head<2>();
  const double beyond = error.norm() - p_.step_adjustment_dead_band;
  if (p_.step_adjustment_gain > 0.0 && beyond > 0.0) {
    const double length = std::min(p_.step_adjustment_gain * beyond, p_.max_step_adjustment);
    step_offset_.head<2>() = length * error.normalized();
  }
  momentum_rate_.tail<3>() = -p_.angular_momentum_kd * momentum_.tail<3>();
}

// The dynamics' base rows; per foot its contact (or no wrench) and its wrench's limits.
void WalkingQp::fill_constraints(const WalkingTargets& t) {
  A_eq_.setZero();
  b_eq_.setZero();
  A_eq_.topLeftCorner(6, N_) = M_.topRows(6);
  A_eq_.block(0, N_, 6, 12) = -Jfeet_.leftCols<6>().transpose();
  b_eq_.head<6>() = -h_.head<6>();
  C_.topRows(2 * kRowsPerFoot).setZero();
  const double weight_of_robot = -mass_ * p_.gravity.z();
  for (int f = 0; f < 2; ++f) {
    const double w = t.contact_weight[f];
    contact_[f] = w > 0.0;
    const int row = 6 + 6 * f;
    if (contact_[f]) {
      A_eq_.block(row, 0, 6, N_) = Jfeet_.middleRows(6 * f, 6);
      b_eq_.segment<6>(row) = -dj_nu_feet_.segment<6>(6 * f);
    } else {
      A_eq_.block<6, 6>(row, N_ + 6 * f).setIdentity();
    }
    // Rows in the sole frame, on the world-axes wrench: blockdiag(Rᵀ, Rᵀ).
    const Eigen::Matrix3d Rt = foot_rotation_[f].transpose();
    const int c = kRowsPerFoot * f;
    C_.block<kFootConstraintRows, 3>(c, N_ + 6 * f).noalias() = foot_rows_.leftCols<3>() * Rt;
    C_.block<kFootConstraintRows, 3>(c, N_ + 6 * f + 3).noalias() = foot_rows_.rightCols<3>() * Rt;
    C_.block<1, 3>(c + kFootConstraintRows, N_ + 6 * f).noalias() =
        -foot_rows_.block<1, 3>(0, 0) * Rt;
    if (contact_[f]) {
      d_.segment<kRowsPerFoot>(c).setZero();
      d_[c] = w * p_.min_normal_force;
      d_[c + kFootConstraintRows] = -w * p_.max_normal_force * weight_of_robot;
    } else {
      d_.segment<kRowsPerFoot>(c).setConstant(-1.0);  // its wrench is 0 by an equality
    }
  }
  // The joints' torque limits: −τ_max ≤ [M_j  −J_jᵀ] x + h_j ≤ τ_max.
  torque_map_.leftCols(N_) = M_.bottomRows(n_);
  torque_map_.rightCols<12>() = -Jfeet_.rightCols(n_).transpose();
  C_.middleRows(2 * kRowsPerFoot, n_) = torque_map_;
  C_.bottomRows(n_) = -torque_map_;
  d_.segment(2 * kRowsPerFoot, n_) = -effort_ - h_.tail(n_);
  d_.tail(n_) = -effort_ + h_.tail(n_);
}

void WalkingQp::add_acceleration_task(const Eigen::Ref<const Eigen::MatrixXd>& J,
                                      const Eigen::Ref<const Eigen::VectorXd>& b, double weight) {
  H_.topLeftCorner(N_, N_).noalias() += weight * J.transpose() * J;
  g_.head(N_).noalias() -= weight * J.transpose() * b;
}

void WalkingQp::fill_costs(const WalkingTargets& t) {
  H_.setZero();
  g_.setZero();
  const double m2 = mass_ * mass_;

  // Momentum rate, (A f + m g − Ḣ*) / m.
  for (int f = 0; f < 2; ++f) {
    A_.block<3, 3>(0, 6 * f).setIdentity();
    A_.block<3, 3>(3, 6 * f) = skew(foot_[f].position - com_);
    A_.block<3, 3>(3, 6 * f + 3).setIdentity();
  }
  // The angular rows weigh angular_momentum_weight of the linear ones.
  Eigen::Matrix<double, 6, 1> target = momentum_rate_;
  target.head<3>() -= mass_ * p_.gravity;
  const double angular = std::sqrt(p_.angular_momentum_weight);
  A_.bottomRows<3>() *= angular;
  target.tail<3>() *= angular;
  H_.block<12, 12>(N_, N_).noalias() += (p_.momentum_weight / m2) * A_.transpose() * A_;
  g_.segment<12>(N_).noalias() -= (p_.momentum_weight / m2) * A_.transpose() * target;

  // The swinging foot's pose: J ν̇ + J̇ν = a*.
  for (int f = 0; f < 2; ++f) {
    if (contact_[f]) {
      continue;
    }
    const Eigen::Vector4d& v = t.feet_velocity[f];
    const Eigen::Vector4d& a = t.feet_acceleration[f];
    Eigen::Matrix<double, 6, 1> desired;
    desired.head<3>() = a.head<3>() +
                        p_.swing_kp * (t.feet[f].position + step_offset_ - foot_[f].position) +
                        p_.swing_kd * (v.head<3>() - foot_velocity_[f].head<3>());
    const Eigen::Matrix3d target_rotation =
        Eigen::AngleAxisd(t.feet[f].yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    desired.tail<3>() =
        Eigen::Vector3d(0.0, 0.0, a[3]) +
        p_.swing_kp * rotation_vector(target_rotation * foot_rotation_[f].transpose()) +
        p_.swing_kd * (Eigen::Vector3d(0.0, 0.0, v[3]) - foot_velocity_[f].tail<3>());
    desired -= dj_nu_feet_.segment<6>(6 * f);
    add_acceleration_task(Jfeet_.middleRows(6 * f, 6), desired, p_.swing_weight);
  }

  // The torso upright, heading where the planned feet head.
  const double heading = mean_yaw(t.feet[0].yaw, t.feet[1].yaw);
  const Eigen::Matrix3d torso_target =
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix() * torso_offset_;
  Eigen::Vector3d torso_acceleration =
      p_.torso_kp * rotation_vector(torso_target * torso_rotation_.transpose()) -
      p_.torso_kd * (Jtorso_.bottomRows<3>() * nu_);
  torso_acceleration -= dj_nu_torso_.tail<3>();
  add_acceleration_task(Jtorso_.bottomRows<3>(), torso_acceleration, p_.torso_weight);

  // Posture: q̈ = kp (q₀ − q) − kd q̇.
  // The legs' weight apart from the rest's: a firm leg posture holds the legs
  // back from stepping (iCub 3 fell at its first steps with 0.3). A firm rest
  // keeps the arms near their posture, but the QP then lacks them to damp the
  // angular momentum (iCub 3 fell at the turn with 1.0); both light by default,
  // and the arms swing wide (README.md, "Limits").
  task_b_ = posture_kp_ * (posture_ - state_.q) - posture_kd_ * state_.dq;
  for (int j = 0; j < n_; ++j) {
    const double w = leg_joint_[j] ? p_.leg_posture_weight : p_.posture_weight;
    H_(6 + j, 6 + j) += w;
    g_[6 + j] -= w * task_b_[j];
  }

  // Torques, τ = [M_j  −J_jᵀ] x + h_j, divided by m.
  H_.noalias() += (p_.torque_weight / m2) * torque_map_.transpose() * torque_map_;
  g_.noalias() += (p_.torque_weight / m2) * torque_map_.transpose() * h_.tail(n_);

  // Regularisation; the feet moments a little more (the CoP near the sole's centre).
  H_.diagonal().head(N_).array() += p_.acceleration_weight;
  H_.diagonal().tail<12>().array() += p_.wrench_weight / m2;
  for (int f = 0; f < 2; ++f) {
    H_.diagonal().segment<3>(N_ + 6 * f + 3).array() += p_.foot_moment_weight / m2;
  }
}

void WalkingQp::compute(const WalkingTargets& targets) {
  evaluate_model();
  momentum_rate_target(targets);
  fill_constraints(targets);
  fill_costs(targets);
  if (qp_.solve(H_, g_, A_eq_, b_eq_, C_, d_) != qp::Status::optimal) {
    ++qp_failures_;  // the last torques stay
    return;
  }
  const Eigen::VectorXd& x = qp_.solution();
  wrench_ = x.tail<12>();
  tau_ = h_.tail(n_);
  tau_.noalias() += torque_map_ * x;
}

}  // namespace wbi::controllers::walking
