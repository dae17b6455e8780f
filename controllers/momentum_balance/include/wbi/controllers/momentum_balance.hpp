// Momentum-based balancing on two feet (Nava et al. 2016, see README.md):
//   1. desired rate of change of the centroidal momentum
//        ṗ* = m (ẍ_d − K_p (x − x_d) − K_d (ẋ − ẋ_d)),   L̇* = −K_L L
//   2. joint torques from the constrained floating-base dynamics, affine in
//      the feet wrenches f = (f_L, f_R), with a postural task in the null space:
//        τ(f) = τ_c − T f
//   3. one QP in f: track (ṗ*, L̇*) with Ḣ = A f + m g, keep τ(f) small,
//      subject to unilateral, friction-pyramid, centre-of-pressure and
//      torsional constraints per foot.
// Written against the whole-body interface only; torque mode. Allocates
// nothing per update after construction.
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <wbi/qp/dense_qp.hpp>

#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers {

struct MomentumBalanceParameters {
  std::string left_sole = "l_sole";  // contact frames: z normal to the ground, x forward
  std::string right_sole = "r_sole";
  // Foot support rectangle in the sole frame [m] (the CoP must stay inside).
  double foot_x_min = -0.09, foot_x_max = 0.09, foot_y_min = -0.035, foot_y_max = 0.035;
  double friction = 0.5;              // μ of the pyramid (inscribed: |f_x|, |f_y| ≤ μ/√2 f_z)
  double torsional_friction = 0.01;   // |τ_z| ≤ this × f_z [m]
  double min_normal_force = 10.0;     // [N] per foot: both feet stay loaded
  double com_kp = 100.0;              // [1/s²]
  double com_kd = 20.0;               // [1/s]
  double angular_momentum_kd = 5.0;   // [1/s]
  double posture_bandwidth_hz = 2.0;  // null-space joint PD from the mass-matrix diagonal
  double torque_weight = 1e-3;        // of ‖τ‖² against ‖Ḣ − Ḣ*‖² [N²/(N m)²]
  double wrench_weight = 1e-6;        // ‖f‖² regularisation
  // Extra weight on the feet moments: among the wrenches that give the same momentum
  // rate, prefer shifting load between the feet to loading a foot's edge (the CoP
  // near the centre keeps the foot flat on a compliant ground).
  double foot_moment_weight = 1e-2;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
};

class MomentumBalance {
 public:
  // robot: initialized, with the controlled joints. q_posture: the postural
  // task's joint reference. Throws wbi::Error naming a wrong size, an unknown
  // sole frame or a bad parameter.
  MomentumBalance(WholeBodyInterface& robot, MomentumBalanceParameters parameters,
                  Eigen::VectorXd q_posture);

  // Puts the controlled joints in torque mode.
  void start();
  // One tick: read_state() then control(). No allocation.
  void update(ReadMode mode = ReadMode::latest);
  // The two halves of a tick, for a caller whose CoM reference depends on the
  // state's time: reads q, q̇, base pose and velocity of one estimate (its stamp) …
  Stamp read_state(ReadMode mode = ReadMode::latest);
  // … then evaluates the model, solves the QP and sends τ.
  void control();
  // The same without sending τ (torques()), for a caller that sends it.
  void compute();

  // The fields used per tick (com_kp, com_kd, angular_momentum_kd,
  // torque_weight, wrench_weight, foot_moment_weight) from `parameters`; the
  // others stay as constructed. Throws wbi::Error as the constructor does.
  void set_tracking(const MomentumBalanceParameters& parameters);

  // CoM reference (position, velocity, acceleration) in the world.
  void set_com_reference(const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                         const Eigen::Vector3d& acceleration);

  const Eigen::Vector3d& com() const { return com_; }  // at the last control()
  Eigen::Vector3d com_of_state();                      // of the last read_state()
  Eigen::Vector3d feet_center_of_state();              // middle of the soles, likewise
  const Eigen::Vector3d& com_reference() const { return com_desired_; }
  const Eigen::VectorXd& torques() const { return tau_; }
  // Feet wrenches of the last QP: (force, moment about the sole), left then right, world axes.
  const Eigen::Matrix<double, 12, 1>& wrenches() const { return wrench_; }
  qp::Status qp_status() const { return qp_.status(); }
  std::uint64_t qp_failures() const { return qp_failures_; }
  std::uint64_t last_seq() const { return last_seq_; }
  double mass() const { return mass_; }

 private:
  void build_constraints();
  void compute_torque_map();
  void solve_wrenches();

  WholeBodyInterface& robot_;
  MomentumBalanceParameters p_;
  int n_;
  int left_, right_;
  Eigen::VectorXd q_posture_, posture_kp_, posture_kd_;
  Eigen::VectorXd joint_inertia_;  // M_jj at the posture: the weights of Λ†
  double mass_ = 0.0;

  // state
  RobotState state_;  // read whole by read_state()
  Transform world_H_sole_ = Transform::Identity();
  std::uint64_t last_seq_ = 0;

  // model quantities
  Eigen::MatrixXd M_, Jc_, Minv_Jct_, Lambda_, Lambda_pinv_, gram_solve_, null_, gram_;
  Eigen::Matrix<double, 12, 12> Jc_Minv_Jct_;
  Eigen::Matrix<double, 12, 1> constraint_bias_;  // Jc M⁻¹ h − J̇ν
  Eigen::VectorXd h_, dj_nu_, tau_0_;
  Eigen::LLT<Eigen::MatrixXd> mass_llt_, gram_llt_;
  Eigen::Vector3d com_ = Eigen::Vector3d::Zero(), com_velocity_ = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 6, 1> momentum_ = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Vector3d sole_position_[2];
  Eigen::Matrix3d sole_rotation_[2];

  // references
  Eigen::Vector3d com_desired_ = Eigen::Vector3d::Zero(),
                  com_velocity_desired_ = Eigen::Vector3d::Zero(),
                  com_acceleration_desired_ = Eigen::Vector3d::Zero();
  bool com_reference_set_ = false;

  // τ(f) = τ_c − T f; the QP
  Eigen::VectorXd tau_c_, tau_;
  Eigen::MatrixXd T_;
  Eigen::Matrix<double, 6, 12> A_ = Eigen::Matrix<double, 6, 12>::Zero();
  Eigen::Matrix<double, 6, 1> momentum_rate_desired_ = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::MatrixXd qp_H_, qp_A_eq_, qp_C_;
  Eigen::VectorXd qp_g_, qp_b_eq_, qp_d_;
  Eigen::Matrix<double, 11, 6> foot_constraints_;  // in the sole frame: rows · (f, τ) ≥ 0
  Eigen::Matrix<double, 12, 1> wrench_ = Eigen::Matrix<double, 12, 1>::Zero();
  qp::DenseQp qp_;
  std::uint64_t qp_failures_ = 0;
};

}  // namespace wbi::controllers
