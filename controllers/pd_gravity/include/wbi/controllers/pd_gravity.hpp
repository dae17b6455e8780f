// PD plus gravity compensation, the paper's first example:
//   τ = G_j(q) − K_p (q − q_d) − K_d q̇
// G_j: the joint rows of the gravity forces at the estimated posture, with
// the base pose as read from the State element (constant for a fixed base).
// Written against the whole-body interface only.
#pragma once

#include <span>

#include <Eigen/Core>

#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers {

// K_p and K_d: symmetric positive definite [dofs × dofs] matrices (the
// paper's form; any such pair makes PD + gravity converge, Takegaki and
// Arimoto 1981). Diagonal gains are the usual hand-tuned case.
struct PdGravityGains {
  Eigen::MatrixXd kp;  // N m/rad
  Eigen::MatrixXd kd;  // N m s/rad

  static PdGravityGains diagonal(const Eigen::VectorXd& kp, const Eigen::VectorXd& kd);
  // Every mode of the arm critically damped at bandwidth_hz about the posture
  // whose joint-space inertia is M_jj (the mass matrix's joint block):
  // K_p = ω² M_jj, K_d = 2ω M_jj. Scaling by the diagonal of M_jj alone
  // leaves coupled modes with up to max eig(M_jj⁻¹ diag M_jj) times the
  // damping gain (19 for the project's arm), which a few milliseconds of
  // loop delay destabilise (tests/multihost/README.md).
  static PdGravityGains from_inertia(const Eigen::MatrixXd& joint_inertia, double bandwidth_hz);
};

class PdGravity {
 public:
  // robot: initialized, with the controlled joints of this controller.
  // Throws wbi::Error when a size does not match robot.dofs().
  PdGravity(WholeBodyInterface& robot, PdGravityGains gains, Eigen::VectorXd q_desired,
            Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81));
  // Zero gains and target, sized for robot.dofs(): set them before computing.
  explicit PdGravity(WholeBodyInterface& robot);

  // Puts the controlled joints in torque mode.
  void start();
  // One control tick: read state, compute τ, send it. No allocation.
  void update(ReadMode mode = ReadMode::latest);
  // The same without sending τ (torques()), for a caller that adds to it.
  void compute(ReadMode mode = ReadMode::latest);

  void set_reference(const ConstVectorRef& q_desired);
  // New gains of the same size (no allocation). Throws wbi::Error naming a wrong size.
  void set_gains(const Eigen::MatrixXd& kp, const Eigen::MatrixXd& kd);
  // The gains where the law holds them, the one copy: a controller computes
  // them in place (from the inertia, given ones), keeping their sizes.
  PdGravityGains& gains() { return gains_; }
  const PdGravityGains& gains() const { return gains_; }
  // The PD terms times `scale` (a live gain_scale); the gains stay as they are.
  void set_gain_scale(double scale) { gain_scale_ = scale; }
  // Only these joints' errors and velocities enter the PD terms (a controller
  // commanding some of a host's joints: the others couple in nothing); empty:
  // every joint. No allocation.
  void set_own_joints(std::span<const int> own);
  const RobotState& state() const { return state_; }  // of the last update
  const Eigen::VectorXd& torques() const { return tau_; }
  // max |q − q_d| at the last update [rad]
  double max_error() const { return max_error_; }

 private:
  WholeBodyInterface& robot_;
  PdGravityGains gains_;
  double gain_scale_ = 1.0;
  Eigen::VectorXd own_;  // 1 for a joint whose error enters, 0 for one that does not
  bool all_own_ = true;  // every joint's: the products skip the mask
  Eigen::VectorXd q_desired_;
  Eigen::Vector3d gravity_;
  RobotState state_;  // read whole each tick
  Eigen::VectorXd error_, velocity_, g_, tau_;
  double max_error_ = 0.0;
};

}  // namespace wbi::controllers
