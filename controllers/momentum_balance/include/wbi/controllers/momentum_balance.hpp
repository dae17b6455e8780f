// Momentum-based balancing on two feet (Nava et al. 2016, see README.md):
//   1. desired rate of change of the centroidal momentum
//        ṗ* = m (ẍ_d − K_p (x − x_d) − K_d (ẋ − ẋ_d)),   L̇* = −K_L L
//   2. joint torques from the constrained floating-base dynamics, affine in
//      the feet wrenches f = (f_L, f_R), with a postural task in the null space:
//        τ(f) = τ_c − T f
//   3. one QP in f: track (ṗ*, L̇*) with Ḣ = A f + m g, keep τ(f) small,
//      subject to unilateral, friction-pyramid, centre-of-pressure and
//      torsional constraints per foot.
//   4. optionally (estimated_contact_forces), the feet wrenches the state element
//      estimates from F/T sensors (EstimateKind::external_wrench) correct the
//      torques, so that the feet carry the net wrench planned. With a model error
//      (joint friction, soft contacts) the torques for f give f + d; a low-passed
//      estimate of d from what the feet carried, d̂ = LP(f̂ − f_cmd), is taken
//      off in its net wrench: τ = τ_c + k T A⁺A d̂ − T f, i.e. f_cmd = f − k A⁺A d̂,
//      and the net wrench misses by (1 − k) A d. In the static model
//      f̂ − f_cmd = d whatever f_cmd is, so the correction does not feed back
//      on itself.
// Written against the whole-body interface only; torque mode. Allocates
// nothing per update after construction.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

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
  // Contact forces from the state element (4. above): f̂ per foot is the sum of
  // the wrenches estimated on the links of left_wrench_links and
  // right_wrench_links (each among State::external_wrench_links(); empty: the
  // sole frame itself), about the sole's origin. wrench_correction is k, in
  // [0, 1]; wrench_correction_cutoff_hz the low-pass on d̂.
  bool estimated_contact_forces = false;
  std::vector<std::string> left_wrench_links, right_wrench_links;
  double wrench_correction = 0.5;
  double wrench_correction_cutoff_hz = 5.0;
};

class MomentumBalance {
 public:
  // robot: initialized, with the controlled joints. q_posture: the postural
  // task's joint reference. Throws wbi::Error naming a wrong size, an unknown
  // sole frame or a bad parameter.
  MomentumBalance(WholeBodyInterface& robot, MomentumBalanceParameters parameters,
                  Eigen::VectorXd q_posture);

  // Puts the controlled joints in torque mode; the wrench correction starts anew.
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
  // torque_weight, wrench_weight, foot_moment_weight, wrench_correction) from `parameters`; the
  // others stay as constructed. Throws wbi::Error as the constructor does.
  void set_tracking(const MomentumBalanceParameters& parameters);

  // CoM reference (position, velocity, acceleration) in the world.
  void set_com_reference(const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                         const Eigen::Vector3d& acceleration);

  const Eigen::Vector3d& com() const { return com_; }  // at the last control()
  Eigen::Vector3d com_of_state();                      // of the last read_state()
  Eigen::Vector3d feet_center_of_state();              // middle of the soles, likewise
  Eigen::Vector3d feet_center() const {                // the same at the last control()
    return 0.5 * (sole_position_[0] + sole_position_[1]);
  }
  const Eigen::Vector3d& com_reference() const { return com_desired_; }
  const Eigen::VectorXd& torques() const { return tau_; }
  // Feet wrenches of the last QP: (force, moment about the sole), left then right, world axes.
  const Eigen::Matrix<double, 12, 1>& wrenches() const { return wrench_; }
  // The feet wrenches the state element estimated, likewise, and d̂, the
  // low-passed difference from the wrenches the torques were for (zero unless
  // estimated_contact_forces).
  const Eigen::Matrix<double, 12, 1>& estimated_wrenches() const { return wrench_estimated_; }
  const Eigen::Matrix<double, 12, 1>& wrench_disturbance() const { return wrench_disturbance_; }
  // What the feet carried beyond the plan, low-passed as d̂: LP(f̂ − f). With the
  // correction it is (1 − k) d̂.
  const Eigen::Matrix<double, 12, 1>& wrench_miss() const { return wrench_miss_; }
  // The net wrench of feet wrenches w about the CoM, (force, moment), at the last
  // control(): A w, the part of w that changes the momentum.
  Eigen::Matrix<double, 6, 1> net_wrench(const Eigen::Matrix<double, 12, 1>& w) const {
    return A_ * w;
  }
  qp::Status qp_status() const { return qp_.status(); }
  std::uint64_t qp_failures() const { return qp_failures_; }
  std::uint64_t last_seq() const { return last_seq_; }
  double mass() const { return mass_; }

 private:
  void build_constraints();
  void compute_torque_map();
  void solve_wrenches();
  void resolve_wrench_links();
  void read_estimated_wrenches();
  void correct_for_wrench_disturbance();
  void compute_momentum_map();

  WholeBodyInterface& robot_;
  MomentumBalanceParameters p_;
  int n_;
  int left_, right_;
  Eigen::VectorXd q_posture_, posture_kp_, posture_kd_;
  Eigen::VectorXd joint_inertia_;  // M_jj at the posture: the weights of Λ†
  double mass_ = 0.0;

  // state
  RobotState state_;  // read whole by read_state()
  Transform world_H_sole_ = Transform::Identity(), world_H_link_ = Transform::Identity();
  std::uint64_t last_seq_ = 0;
  std::int64_t stamp_ns_ = 0, corrected_stamp_ns_ = -1;  // of the state; of the last d̂ update

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
  // estimated_contact_forces: per foot, the estimated links (index in
  // external_wrench_links(), frame index), and their sum about the soles.
  struct WrenchLink {
    int foot, estimate, frame;
  };
  std::vector<WrenchLink> wrench_links_;
  Eigen::Matrix<double, 6, 1> link_wrench_ = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 12, 1> wrench_estimated_ = Eigen::Matrix<double, 12, 1>::Zero();
  Eigen::Matrix<double, 12, 1> wrench_disturbance_ = Eigen::Matrix<double, 12, 1>::Zero();
  Eigen::Matrix<double, 12, 1> wrench_commanded_ = Eigen::Matrix<double, 12, 1>::Zero();  // f − k d̂
  Eigen::Matrix<double, 12, 1> wrench_correction_ = Eigen::Matrix<double, 12, 1>::Zero();
  Eigen::Matrix<double, 12, 1> wrench_planned_ = Eigen::Matrix<double, 12, 1>::Zero();  // f
  Eigen::Matrix<double, 12, 1> wrench_miss_ = Eigen::Matrix<double, 12, 1>::Zero();  // LP(f̂ − f)
  qp::DenseQp qp_;
  std::uint64_t qp_failures_ = 0;
};

}  // namespace wbi::controllers
