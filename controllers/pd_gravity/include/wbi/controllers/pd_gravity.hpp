// PD plus gravity compensation, the paper's first example:
//   τ = G_j(q) − K_p (q − q_d) − K_d q̇
// G_j: the joint rows of the gravity forces at the estimated posture, with
// the base pose as read from the State element (constant for a fixed base).
// Written against the whole-body interface only.
#pragma once

#include <Eigen/Core>

#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers {

struct PdGravityGains {
  Eigen::VectorXd kp;  // [dofs] N m/rad
  Eigen::VectorXd kd;  // [dofs] N m s/rad
};

class PdGravity {
 public:
  // robot: initialized, with the controlled joints of this controller.
  // Throws wbi::Error when a size does not match robot.dofs().
  PdGravity(WholeBodyInterface& robot, PdGravityGains gains, Eigen::VectorXd q_desired,
            Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81));

  // Puts the controlled joints in torque mode.
  void start();
  // One control tick: read state, compute τ, send it. No allocation.
  void update(ReadMode mode = ReadMode::latest);

  void set_reference(const ConstVectorRef& q_desired);
  const Eigen::VectorXd& torques() const { return tau_; }
  // max |q − q_d| at the last update [rad]
  double max_error() const { return max_error_; }

 private:
  WholeBodyInterface& robot_;
  PdGravityGains gains_;
  Eigen::VectorXd q_desired_;
  Eigen::Vector3d gravity_;
  Eigen::VectorXd q_, dq_, g_, tau_;
  Transform world_H_base_ = Transform::Identity();
  double max_error_ = 0.0;
};

}  // namespace wbi::controllers
