#include "wbi/controllers/pd_gravity.hpp"

#include <string>

namespace wbi::controllers {

namespace {
void require_size(const char* what, Eigen::Index size, int dofs) {
  if (size != dofs) {
    throw Error(std::string("PD + gravity: ") + what + " has size " + std::to_string(size) +
                ", the controller has " + std::to_string(dofs) + " joints");
  }
}
}  // namespace

PdGravity::PdGravity(WholeBodyInterface& robot, PdGravityGains gains, Eigen::VectorXd q_desired,
                     Eigen::Vector3d gravity)
    : robot_(robot), gains_(std::move(gains)), q_desired_(std::move(q_desired)), gravity_(gravity) {
  const int n = robot_.dofs();
  require_size("kp", gains_.kp.size(), n);
  require_size("kd", gains_.kd.size(), n);
  require_size("q_desired", q_desired_.size(), n);
  q_.setZero(n);
  dq_.setZero(n);
  tau_.setZero(n);
  g_.setZero(n + 6);
}

void PdGravity::start() { robot_.set_control_mode(ControlMode::torque); }

void PdGravity::set_reference(const ConstVectorRef& q_desired) {
  require_size("q_desired", q_desired.size(), robot_.dofs());
  q_desired_ = q_desired;
}

// The paper's loop: read the state, compute the gravity bias forces, send torques.
void PdGravity::update(ReadMode mode) {
  // q, q̇ and the base pose of one and the same estimate: a newer one may arrive
  // between two reads, so read again until the three agree.
  Stamp position = robot_.read_estimates(EstimateKind::joint_position, q_, mode);
  Stamp velocity = robot_.read_estimates(EstimateKind::joint_velocity, dq_);
  Stamp base = robot_.read_base_pose(world_H_base_);
  while (position.seq != velocity.seq || velocity.seq != base.seq) {
    position = robot_.read_estimates(EstimateKind::joint_position, q_);
    velocity = robot_.read_estimates(EstimateKind::joint_velocity, dq_);
    base = robot_.read_base_pose(world_H_base_);
  }
  robot_.gravity_forces(q_, world_H_base_, gravity_, g_);
  tau_ = g_.tail(robot_.dofs()) - gains_.kp.cwiseProduct(q_ - q_desired_) -
         gains_.kd.cwiseProduct(dq_);
  max_error_ = (q_ - q_desired_).cwiseAbs().maxCoeff();
  robot_.set_control_reference(tau_);
}

}  // namespace wbi::controllers
