// The joint accelerations a model predicts from the torques a robot is told to
// apply, for fusion with the encoders (model_kalman.hpp; the estimator
// component's `accelerations: model`).
//
// Free joints and bodies, forward dynamics (model/aba.hpp):
//   ν̇_free = M(q)⁻¹ (Bτ_net − h(q, ν)),   M with the motors' armature,
// τ_net the command less the joints' losses, which a URDF does not have:
// viscous damping d q̇ and, on a sliding joint, Coulomb friction f sign(q̇).
//
// Contacts and stiction as constraints (Featherstone, "Rigid Body Dynamics
// Algorithms", 2008, §8.1): a held contact frame does not accelerate,
// J_c ν̇ + J̇_c ν = 0, and a joint slower than v_s may be stuck, q̈_j = 0. Their
// forces λ are what that takes:
//   ν̇ = ν̇_free + M⁻¹ Jᵀ λ,   (J M⁻¹ Jᵀ) λ = −(J̇ ν + J ν̇_free).
// A stuck joint whose λ_j exceeds its friction f_j cannot be held: it slides,
// pushed by f_j sign(λ_j), and λ is solved again (one pass of the
// complementarity problem: joints stick or slide for many ticks at a time).
//
// Why constraints rather than the estimated contact wrenches as known forces:
// feet are light, so forward dynamics with given foot wrenches turns every
// torque error into hundreds of rad/s² at the ankles; held by the ground, the
// same error moves the whole body a little. Why stiction: balancing iCub 3 in
// MuJoCo (1 N·m of friction on its legs) the stuck joints absorb the
// balancer's torque changes, which a frictionless model turned into 1.6 rad/s²
// of q̈ error (the truth: 0.27 rad/s² RMS). Contact frames on one body (iCub
// 3's two plates under a foot) make one constraint.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "wbi/model/data.hpp"
#include "wbi/model/model.hpp"

namespace wbi::estimation {

// The joints' losses between the command and the links, per joint (≥ 0).
struct JointLosses {
  Eigen::VectorXd damping;        // d [N m s/rad]; empty: none
  Eigen::VectorXd friction;       // f [N m]; empty: none
  double stick_velocity = 0.005;  // v_s [rad/s], > 0
};

class ModelAccelerations {
 public:
  // `model` with its armature; `contact_frames`: the model frames that may be
  // held. Throws std::invalid_argument naming a bad size, value or frame.
  ModelAccelerations(model::Model model, JointLosses losses, std::vector<int> contact_frames);

  // ν̇ [nv] at q [nq] and ν [nv] under the commanded joint torques tau
  // [n_joints], the contact frames with held[c] != 0 held (one per given
  // frame; a wrong count throws). Never allocates.
  const Eigen::VectorXd& update(const Eigen::VectorXd& q, const Eigen::VectorXd& nu,
                                const Eigen::VectorXd& tau, std::span<const char> held);

  // Of the last update: joints held by their friction.
  int stuck_joints() const { return stuck_count_; }
  const model::Model& model() const { return model_; }

 private:
  // λ of the active rows (held contacts, stuck joints) for ddq_ (ν̇_free),
  // gathered at the top of the preallocated matrices: only they are solved.
  void solve_constraints();

  model::Model model_;
  model::Data data_;
  JointLosses losses_;
  std::vector<int> contact_frames_;  // one per body
  std::vector<int> contact_of_;      // for each given frame, its body's row block
  std::vector<char> body_held_;      // per row block, this update
  std::vector<char> stuck_;          // per joint
  int stuck_count_ = 0;
  Eigen::VectorXd tau_net_;    // [nv], the base's entries 0
  Eigen::VectorXd ddq_;        // [nv]
  Eigen::VectorXd delta_tau_;  // [nv] friction of released joints
  // The active constraints in the leading rows (at most 6 bodies + n_joints):
  // the held contacts' (contact_rows_ of them), then the stuck joints'.
  Eigen::MatrixXd J_;
  Eigen::VectorXd bias_;  // J̇ ν (0 for joints)
  Eigen::Index contact_rows_ = 0;
  Eigen::MatrixXd MinvJt_;  // M⁻¹ Jᵀ
  Eigen::MatrixXd A_;       // J M⁻¹ Jᵀ
  Eigen::VectorXd lambda_;
  Eigen::Index active_rows_ = 0;
  std::vector<int> joint_row_;  // per joint, its row when stuck, else −1
  Eigen::LLT<Eigen::MatrixXd> mass_llt_;
};

}  // namespace wbi::estimation
