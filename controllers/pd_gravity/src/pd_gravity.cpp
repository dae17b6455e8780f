#include "wbi/controllers/pd_gravity.hpp"

#include <cmath>
#include <string>

namespace wbi::controllers {

namespace {
void require_size(const char* what, Eigen::Index size, int dofs) {
  if (size != dofs) {
    throw Error(std::string("PD + gravity: ") + what + " has size " + std::to_string(size) +
                ", the controller has " + std::to_string(dofs) + " joints");
  }
}

void require_square(const char* what, const Eigen::MatrixXd& gain, int dofs) {
  if (gain.rows() != dofs || gain.cols() != dofs) {
    throw Error(std::string("PD + gravity: ") + what + " is " + std::to_string(gain.rows()) + "×" +
                std::to_string(gain.cols()) + ", the controller has " + std::to_string(dofs) +
                " joints");
  }
}
}  // namespace

PdGravityGains PdGravityGains::diagonal(const Eigen::VectorXd& kp, const Eigen::VectorXd& kd) {
  return {kp.asDiagonal(), kd.asDiagonal()};
}

PdGravityGains PdGravityGains::from_inertia(const Eigen::MatrixXd& joint_inertia,
                                            double bandwidth_hz) {
  if (joint_inertia.rows() != joint_inertia.cols()) {
    throw Error("PD + gravity: the joint inertia is not square");
  }
  if (!(bandwidth_hz > 0.0)) {
    throw Error("PD + gravity: the bandwidth must be > 0 Hz, got " + std::to_string(bandwidth_hz));
  }
  const double omega = 2.0 * M_PI * bandwidth_hz;
  return {omega * omega * joint_inertia, 2.0 * omega * joint_inertia};
}

PdGravity::PdGravity(WholeBodyInterface& robot, PdGravityGains gains, Eigen::VectorXd q_desired,
                     Eigen::Vector3d gravity)
    : robot_(robot), gains_(std::move(gains)), q_desired_(std::move(q_desired)), gravity_(gravity) {
  const int n = robot_.dofs();
  require_square("kp", gains_.kp, n);
  require_square("kd", gains_.kd, n);
  require_size("q_desired", q_desired_.size(), n);
  state_ = RobotState(n);
  own_.setOnes(n);
  error_.setZero(n);
  velocity_.setZero(n);
  tau_.setZero(n);
  g_.setZero(n + 6);
}

PdGravity::PdGravity(WholeBodyInterface& robot)
    : PdGravity(robot,
                PdGravityGains{Eigen::MatrixXd::Zero(robot.dofs(), robot.dofs()),
                               Eigen::MatrixXd::Zero(robot.dofs(), robot.dofs())},
                Eigen::VectorXd::Zero(robot.dofs())) {}

void PdGravity::start() { robot_.set_control_mode(ControlMode::torque); }

void PdGravity::set_reference(const ConstVectorRef& q_desired) {
  require_size("q_desired", q_desired.size(), robot_.dofs());
  q_desired_ = q_desired;
}

void PdGravity::set_gains(const Eigen::MatrixXd& kp, const Eigen::MatrixXd& kd) {
  require_square("kp", kp, robot_.dofs());
  require_square("kd", kd, robot_.dofs());
  gains_.kp = kp;
  gains_.kd = kd;
}

void PdGravity::set_own_joints(std::span<const int> own) {
  for (const int j : own) {
    if (j < 0 || j >= own_.size()) {
      throw Error("PD + gravity: own joint " + std::to_string(j) + " is not one of its " +
                  std::to_string(own_.size()));
    }
  }
  own_.setConstant(own.empty() ? 1.0 : 0.0);
  for (const int j : own) {
    own_[j] = 1.0;
  }
  all_own_ = own_.minCoeff() == 1.0;
}

// The paper's loop: read the state, compute the gravity bias forces, send torques.
void PdGravity::update(ReadMode mode) {
  compute(mode);
  robot_.actuators().set_control_reference(tau_);
}

void PdGravity::compute(ReadMode mode) {
  robot_.state().read_robot_state(state_, mode);
  robot_.model().gravity_forces(state_.q, state_.world_H_base, gravity_, g_);
  error_ = state_.q - q_desired_;
  max_error_ = error_.cwiseAbs().maxCoeff();
  const Eigen::VectorXd* velocity = &state_.dq;
  if (!all_own_) {
    error_.array() *= own_.array();
    velocity_ = state_.dq.cwiseProduct(own_);
    velocity = &velocity_;
  }
  tau_ = g_.tail(robot_.dofs());
  tau_.noalias() -= gain_scale_ * (gains_.kp * error_);
  tau_.noalias() -= gain_scale_ * (gains_.kd * *velocity);
}

}  // namespace wbi::controllers
