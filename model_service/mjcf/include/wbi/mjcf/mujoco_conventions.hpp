// Between wbi's state and forces and MuJoCo's, for a model written by write_mjcf.
// Header-only, Eigen only (no MuJoCo include): the caller maps mjData's arrays
// with Eigen::Map and fills MujocoIndex from the mjModel by joint name.
//
//   wbi   q = (p_WB, quat w,x,y,z, s)        ν = (ṗ_B world, ω_B world, ṡ)
//   MuJoCo qpos = (p_WB, quat w,x,y,z, s')   qvel = (ṗ_B world, ω_B body axes, ṡ')
// where s' is s in MuJoCo's dof order. So qvel = T ν with
//   T = [[I, 0, 0], [0, Rᵀ, 0], [0, 0, P]],  R = R_WB,  P the joint permutation,
// T orthogonal (T⁻¹ = Tᵀ). Generalized forces map by power, τᵀν = τ_mjᵀ qvel:
// τ = Tᵀ τ_mj. And because d(Rᵀ)/dt ω_B = −ω_b × ω_b = 0, Ṫ ν = 0, so
// accelerations map like velocities (qacc = T ν̇) and
//   M = Tᵀ M_mj T,   h = Tᵀ qfrc_bias,   ν̇ = Tᵀ qacc      — exactly, at any velocity.
// A fixed-base model has T = P. Nothing here allocates.
#pragma once

#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "wbi/model/model.hpp"

namespace wbi::mjcf {

// Where MuJoCo keeps each joint of the wbi model, e.g. from the mjModel m:
//   id = mj_name2id(m, mjOBJ_JOINT, model.joint_name[k].c_str());
//   index.qpos[k] = m->jnt_qposadr[id];  index.dof[k] = m->jnt_dofadr[id];
// The free joint of a floating model written by write_mjcf is MuJoCo's first
// joint: qpos 0…6, dofs 0…5.
struct MujocoIndex {
  std::vector<int> qpos;  // per wbi joint k: its address in qpos
  std::vector<int> dof;   // per wbi joint k: its address in qvel (dof index)
};

namespace detail {
inline Eigen::Matrix3d base_rotation(const Eigen::Ref<const Eigen::VectorXd>& q) {
  return Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized().toRotationMatrix();
}
inline void check_index(const wbi::model::Model& model, const MujocoIndex& index) {
  if (index.qpos.size() != static_cast<std::size_t>(model.n_joints) ||
      index.dof.size() != static_cast<std::size_t>(model.n_joints)) {
    throw std::invalid_argument("MujocoIndex: needs one qpos and one dof address per joint");
  }
}
}  // namespace detail

// q (wbi) → qpos (MuJoCo). Same layout of the base; joints permuted.
inline void wbi_q_to_mujoco_qpos(const wbi::model::Model& model, const MujocoIndex& index,
                                 const Eigen::Ref<const Eigen::VectorXd>& q,
                                 Eigen::Ref<Eigen::VectorXd> qpos) {
  detail::check_index(model, index);
  qpos.head(model.base_nq) = q.head(model.base_nq);
  for (int k = 0; k < model.n_joints; ++k) {
    qpos[index.qpos[static_cast<std::size_t>(k)]] = q[model.base_nq + k];
  }
}

inline void mujoco_qpos_to_wbi_q(const wbi::model::Model& model, const MujocoIndex& index,
                                 const Eigen::Ref<const Eigen::VectorXd>& qpos,
                                 Eigen::Ref<Eigen::VectorXd> q) {
  detail::check_index(model, index);
  q.head(model.base_nq) = qpos.head(model.base_nq);
  for (int k = 0; k < model.n_joints; ++k) {
    q[model.base_nq + k] = qpos[index.qpos[static_cast<std::size_t>(k)]];
  }
}

// qvel = T ν (also qacc = T ν̇: Ṫν = 0). q gives R_WB.
inline void wbi_nu_to_mujoco_qvel(const wbi::model::Model& model, const MujocoIndex& index,
                                  const Eigen::Ref<const Eigen::VectorXd>& q,
                                  const Eigen::Ref<const Eigen::VectorXd>& nu,
                                  Eigen::Ref<Eigen::VectorXd> qvel) {
  detail::check_index(model, index);
  if (model.floating_base) {
    const Eigen::Matrix3d R = detail::base_rotation(q);
    qvel.head<3>() = nu.head<3>();
    qvel.segment<3>(3) = R.transpose() * nu.segment<3>(3);
  }
  for (int k = 0; k < model.n_joints; ++k) {
    qvel[index.dof[static_cast<std::size_t>(k)]] = nu[model.base_nv + k];
  }
}

// ν = Tᵀ qvel (also ν̇ = Tᵀ qacc).
inline void mujoco_qvel_to_wbi_nu(const wbi::model::Model& model, const MujocoIndex& index,
                                  const Eigen::Ref<const Eigen::VectorXd>& q,
                                  const Eigen::Ref<const Eigen::VectorXd>& qvel,
                                  Eigen::Ref<Eigen::VectorXd> nu) {
  detail::check_index(model, index);
  if (model.floating_base) {
    const Eigen::Matrix3d R = detail::base_rotation(q);
    nu.head<3>() = qvel.head<3>();
    nu.segment<3>(3) = R * qvel.segment<3>(3);
  }
  for (int k = 0; k < model.n_joints; ++k) {
    nu[model.base_nv + k] = qvel[index.dof[static_cast<std::size_t>(k)]];
  }
}

// τ = Tᵀ τ_mj: a MuJoCo generalized force (qfrc_bias, qfrc_passive, qfrc_constraint,
// qfrc_actuator …) as wbi's, whose base part is the force and the moment about p_B
// in world axes. Tᵀ has the same form as the qvel → ν map.
inline void mujoco_force_to_wbi(const wbi::model::Model& model, const MujocoIndex& index,
                                const Eigen::Ref<const Eigen::VectorXd>& q,
                                const Eigen::Ref<const Eigen::VectorXd>& force_mj,
                                Eigen::Ref<Eigen::VectorXd> force) {
  mujoco_qvel_to_wbi_nu(model, index, q, force_mj, force);
}

// τ_mj = T τ (T⁻ᵀ = T): a wbi generalized force (e.g. joint torques from a
// controller, or a base wrench) as MuJoCo's qfrc_applied.
inline void wbi_force_to_mujoco(const wbi::model::Model& model, const MujocoIndex& index,
                                const Eigen::Ref<const Eigen::VectorXd>& q,
                                const Eigen::Ref<const Eigen::VectorXd>& force,
                                Eigen::Ref<Eigen::VectorXd> force_mj) {
  wbi_nu_to_mujoco_qvel(model, index, q, force, force_mj);
}

// M = Tᵀ M_mj T. M_mj is MuJoCo's dense mass matrix (mj_fullM, symmetric).
inline void mujoco_mass_matrix_to_wbi(const wbi::model::Model& model, const MujocoIndex& index,
                                      const Eigen::Ref<const Eigen::VectorXd>& q,
                                      const Eigen::Ref<const Eigen::MatrixXd>& M_mj,
                                      Eigen::Ref<Eigen::MatrixXd> M) {
  detail::check_index(model, index);
  const int nb = model.base_nv;
  // ν index → MuJoCo dof index, base first
  auto dof = [&](int v) { return v < nb ? v : index.dof[static_cast<std::size_t>(v - nb)]; };
  for (int r = 0; r < model.nv; ++r) {
    for (int c = 0; c < model.nv; ++c) {
      M(r, c) = M_mj(dof(r), dof(c));  // P part: a permutation of rows and columns
    }
  }
  if (model.floating_base) {
    // the angular base rows/columns: ω_b = Rᵀ ω_B, so M[ω, ·] = R M_mj[ω_b, ·]
    const Eigen::Matrix3d R = detail::base_rotation(q);
    for (int c = 0; c < model.nv; ++c) {
      const Eigen::Vector3d column = M.block<3, 1>(3, c);
      M.block<3, 1>(3, c) = R * column;
    }
    for (int r = 0; r < model.nv; ++r) {
      const Eigen::RowVector3d row = M.block<1, 3>(r, 3);
      M.block<1, 3>(r, 3) = row * R.transpose();
    }
  }
}

}  // namespace wbi::mjcf
