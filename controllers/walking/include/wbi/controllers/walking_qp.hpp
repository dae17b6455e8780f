// Whole-body control of a walking humanoid: one QP per tick in the robot's
// accelerations and the feet wrenches, x = (ν̇, f_L, f_R):
//
//   minimise    Σ_task w ‖J x − b‖²
//   subject to  M_b ν̇ + h_b = J_bᵀ f            the floating base's rows of
//                                               M ν̇ + h = Bτ + Jᵀ f
//               per foot in contact:  J ν̇ + J̇ν = 0, its wrench inside the
//                 friction pyramid with its CoP in the sole and
//                 w f_min ≤ f_z ≤ w f_max, w the contact weight (0..1) that
//                 ramps a foot's load down before it lifts and up after it lands
//               per swinging foot:    f = 0
//               |τ| within the joints' effort limits (URDF)
//
// Tasks, by weight: the centroidal momentum's rate (Ḣ = A f + m g; its linear
// part from the DCM law below, the angular part damped), the swing foot's
// pose, the torso's orientation, a posture, the joint torques, a small
// regularisation. Then τ = M_j ν̇ + h_j − J_jᵀ f (the joints' rows).
//
// DCM law (linear inverted pendulum, ω = √(g / z_c)): with the measured DCM
// ξ = x + ẋ/ω and the plan's ξ_ref, ξ̇_ref, the VRP
//   r* = ξ_ref − ξ̇_ref/ω + (1 + k_ξ/ω)(ξ − ξ_ref)
// makes ξ̇ = ξ̇_ref − k_ξ (ξ − ξ_ref); the CoM acceleration asked of the
// momentum is ω² (x − r*) horizontally, a PD on the planned height
// vertically. The QP keeps the CoP inside the feet: an r* outside them
// saturates instead of being obeyed.
//
// Written against the whole-body interface only; torque mode. Allocates
// nothing per tick after construction.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <wbi/qp/dense_qp.hpp>

#include "wbi/controllers/foot_contact.hpp"
#include "wbi/controllers/walking_plan.hpp"
#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers::walking {

struct WalkingQpParameters {
  std::string left_sole = "l_sole", right_sole = "r_sole";  // z up, x forward
  std::string torso = "root_link";  // the link whose orientation is held upright
  FootSupport support;
  double min_normal_force = 10.0;  // [N] a foot in contact carries at least w × this
  double max_normal_force = 2.0;   // × m g: a foot's normal force at most w × this
  double dcm_gain = 3.0;           // k_ξ [1/s]
  double com_height_kp = 100.0, com_height_kd = 20.0;  // [1/s²], [1/s]
  double angular_momentum_kd = 5.0;                    // [1/s]
  double swing_kp = 600.0, swing_kd = 50.0;            // swing foot pose
  double torso_kp = 200.0, torso_kd = 30.0;            // torso orientation
  // A swinging foot lands off its plan by gain × (the DCM's horizontal error
  // beyond the dead band), at most max_step_adjustment: the step that catches
  // a push. 0: the plan's footsteps exactly.
  double step_adjustment_gain = 0.0;
  double step_adjustment_dead_band = 0.02;  // [m]: walking undisturbed stays inside
  double max_step_adjustment = 0.1;         // [m]
  double posture_bandwidth_hz = 1.0;
  // Task weights, each on a residual in m/s² or rad/s² (the momentum rate and
  // the torques divided by the mass m).
  double momentum_weight = 10.0, swing_weight = 10.0, torso_weight = 1.0;
  double angular_momentum_weight = 1.0;  // × momentum_weight, on the angular part
  double posture_weight = 1e-2;          // the joints that move no sole: torso, arms, neck
  double leg_posture_weight = 1e-2;      // the joints that move a sole
  double torque_weight = 1e-3, acceleration_weight = 1e-6, wrench_weight = 1e-6;
  double foot_moment_weight = 1e-2;  // extra, on the feet moments: the CoP near the sole's centre
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
};

// The plan's values at one tick, read out of the reference input's 16.
struct WalkingTargets {
  Eigen::Vector3d dcm, dcm_velocity, com, com_velocity, com_acceleration;
  std::array<FootPose, 2> feet;                                     // left, right
  std::array<Eigen::Vector4d, 2> feet_velocity, feet_acceleration;  // (ẋ, ẏ, ż, yaw rate)
  std::array<double, 2> contact_weight{1.0, 1.0};

  void read(const WalkingReference& reference);
};

class WalkingQp {
 public:
  // robot: initialized, with the controlled joints. posture: the postural
  // task's joint reference. Throws wbi::Error naming a wrong size, an unknown
  // frame or a bad parameter.
  WalkingQp(WholeBodyInterface& robot, WalkingQpParameters parameters, Eigen::VectorXd posture);

  // The gains and weights from `parameters` (the frames, the support and the
  // force bounds stay as constructed). Throws wbi::Error as the constructor.
  void set_gains(const WalkingQpParameters& parameters);

  // Torque mode on the controlled joints; the torso's upright orientation is
  // taken relative to the feet's heading of this state.
  void start(const RobotState& measured);
  // Reads one state estimate (the latest) and returns its stamp.
  Stamp read_state(ReadMode mode = ReadMode::latest);
  // Model, QP and torques for the targets. No allocation.
  void compute(const WalkingTargets& targets);

  // The plan's values when standing still on the measured state (at read_state()).
  void standing_targets(WalkingTargets& targets);

  const Eigen::VectorXd& torques() const { return tau_; }
  const RobotState& state() const { return state_; }
  const Eigen::Vector3d& com() const { return com_; }
  const Eigen::Vector3d& dcm() const { return dcm_; }
  const FootPose& foot(Foot f) const { return foot_[static_cast<int>(f)]; }
  // Feet wrenches of the last QP: (force, moment about the sole), left then right, world axes.
  const Eigen::Matrix<double, 12, 1>& wrenches() const { return wrench_; }
  bool in_contact(Foot f) const { return contact_[static_cast<int>(f)]; }
  double mass() const { return mass_; }
  std::uint64_t qp_failures() const { return qp_failures_; }
  qp::Status qp_status() const { return qp_.status(); }

 private:
  void evaluate_model();
  void momentum_rate_target(const WalkingTargets& t);
  void fill_constraints(const WalkingTargets& t);
  void fill_costs(const WalkingTargets& t);
  void add_acceleration_task(const Eigen::Ref<const Eigen::MatrixXd>& J,
                             const Eigen::Ref<const Eigen::VectorXd>& b, double weight);

  WholeBodyInterface& robot_;
  WalkingQpParameters p_;
  int n_, N_, nx_;
  std::array<int, 2> sole_;
  int torso_;
  std::vector<bool> leg_joint_;       // per joint: it moves a sole
  Eigen::VectorXd posture_, effort_;  // effort_: the joints' torque limits
  double mass_ = 0.0, posture_kp_ = 0.0, posture_kd_ = 0.0;
  Eigen::Matrix3d torso_offset_ = Eigen::Matrix3d::Identity();  // Rz(feet yaw)ᵀ R_torso standing
  Eigen::Matrix<double, kFootConstraintRows, 6> foot_rows_;

  RobotState state_;
  Transform pose_ = Transform::Identity();
  Eigen::MatrixXd M_, Jfeet_, Jtorso_;
  Eigen::VectorXd h_, nu_;
  Eigen::Matrix<double, 12, 1> dj_nu_feet_;
  Eigen::Matrix<double, 6, 1> dj_nu_torso_, momentum_, momentum_rate_ = {};
  std::array<FootPose, 2> foot_;
  std::array<Eigen::Matrix3d, 2> foot_rotation_;
  std::array<Eigen::Matrix<double, 6, 1>, 2> foot_velocity_;
  std::array<bool, 2> contact_{true, true};
  Eigen::Matrix3d torso_rotation_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d com_ = Eigen::Vector3d::Zero(), com_velocity_ = Eigen::Vector3d::Zero(),
                  dcm_ = Eigen::Vector3d::Zero(), step_offset_ = Eigen::Vector3d::Zero();

  Eigen::MatrixXd H_, A_eq_, C_, torque_map_;
  Eigen::VectorXd g_, b_eq_, d_, task_b_;
  Eigen::Matrix<double, 6, 12> A_ = Eigen::Matrix<double, 6, 12>::Zero();
  Eigen::Matrix<double, 6, Eigen::Dynamic> task_J_;
  Eigen::Matrix<double, 12, 1> wrench_ = Eigen::Matrix<double, 12, 1>::Zero();
  Eigen::VectorXd tau_;
  qp::DenseQp qp_;
  std::uint64_t qp_failures_ = 0;
};

}  // namespace wbi::controllers::walking
