#include "wbi/model/aba.hpp"

#include <Eigen/Cholesky>

#include "../checks.hpp"
#include "../inertias.hpp"
#include "wbi/model/kinematics.hpp"

namespace wbi::model {

const Eigen::VectorXd& forward_dynamics(const Model& model, Data& data, const ConstVectorRef& q,
                                        const ConstVectorRef& nu, const ConstVectorRef& tau,
                                        const Vector3d& gravity,
                                        std::span<const ExternalWrench> wrenches) {
  detail::check_size("forward_dynamics", "nu", nu, model.nv);
  detail::check_size("forward_dynamics", "tau", tau, model.nv);
  for (const ExternalWrench& w : wrenches) {
    detail::check_frame(model, w.frame);
  }
  forward_kinematics(model, data, q);
  detail::world_inertias(model, data);
  Vector6d a_g;
  a_g << -gravity, Vector3d::Zero();
  const Vector3d& p_B = data.p_WB[0];
  data.v[0] = model.floating_base ? detail::base_motion(p_B, nu.head<6>()) : Vector6d::Zero();
  data.IA[0] = data.I_W[0].matrix();
  data.pA[0] = cross_force(data.v[0], data.I_W[0] * data.v[0]);
  // pass 1, out: v_i = v_λ + S q̇,  c_i = v_i × S q̇,  IA_i = I_i,  pA_i = v_i ×* I_i v_i
  for (int i = 1; i < model.n_bodies; ++i) {
    const Vector6d vJ = data.S[i] * nu[model.body_v_index[i]];
    data.v[i] = data.v[model.parent[i]] + vJ;
    data.c[i] = cross_motion(data.v[i], vJ);
    data.IA[i] = data.I_W[i].matrix();
    data.pA[i] = cross_force(data.v[i], data.I_W[i] * data.v[i]);
  }
  // external wrenches (force, moment about p_F) → world-origin forces, subtracted from pA
  for (const ExternalWrench& w : wrenches) {
    const int b = model.frame_body[w.frame];
    const Vector3d p_F = data.p_WB[b] + data.R_WB[b] * model.frame_p_BF[w.frame];
    data.pA[b].head<3>() -= w.wrench.head<3>();
    data.pA[b].tail<3>() -= w.wrench.tail<3>() + p_F.cross(w.wrench.head<3>());
  }
  // pass 2, in: U = IA S, D = Sᵀ U + armature, u = τ − Sᵀ pA;  Ia = IA − U Uᵀ/D;
  // IA_λ += Ia, pA_λ += pA + Ia c + U u/D. The armature (model.hpp) is inertia of the joint
  // coordinate alone: it enters D, so it is in q̈ and in what the parent sees through Ia,
  // but not in IA itself (D > 0 here, so adding an armature of 0 changes no bit).

  for (int i = model.n_bodies - 1; i > 0; --i) {
    const int lambda = model.parent[i];
    data.U[i].noalias() = data.IA[i] * data.S[i];
    data.D[i] = data.S[i].dot(data.U[i]) + model.joint_armature[model.body_joint[i]];
    if (!(data.D[i] > 0.0)) {
      detail::throw_singular(model, i);
    }
    data.u[i] = tau[model.body_v_index[i]] - data.S[i].dot(data.pA[i]);
    const double inv_D = 1.0 / data.D[i];
    data.IA[i].noalias() -= inv_D * data.U[i] * data.U[i].transpose();
    data.IA[lambda] += data.IA[i];
    data.pA[lambda] += data.pA[i] + (inv_D * data.u[i]) * data.U[i];
    data.pA[lambda].noalias() += data.IA[i] * data.c[i];
  }
  // base: IA_0 a_0 + pA_0 = S_B⁻ᵀ τ_B (floating), a_0 = (−g, 0) (fixed)
  if (model.floating_base) {
    Vector6d f_B = tau.head<6>();
    f_B.tail<3>() += p_B.cross(f_B.head<3>());  // S_B⁻ᵀ τ_B: moment about the world origin
    const Eigen::LLT<Matrix6d> llt(data.IA[0]);
    data.a[0] = llt.solve(f_B - data.pA[0]);
    // ν̇_B = S_B⁻¹ (a_0 + (g, 0) − (ṗ_B × ω_B, 0)),  S_B⁻¹ (x, w) = (x − p_B × w, w)
    Vector6d aB = data.a[0] - a_g;
    aB.head<3>() -= nu.head<3>().cross(nu.segment<3>(3));
    data.ddq.head<3>() = aB.head<3>() - p_B.cross(aB.tail<3>());
    data.ddq.segment<3>(3) = aB.tail<3>();
  } else {
    data.a[0] = a_g;
  }
  // pass 3, out: q̈_i = (u_i − U_iᵀ(a_λ + c_i))/D_i,  a_i = a_λ + c_i + S_i q̈_i
  for (int i = 1; i < model.n_bodies; ++i) {
    const int k = model.body_v_index[i];
    const Vector6d a_pre = data.a[model.parent[i]] + data.c[i];
    data.ddq[k] = (data.u[i] - data.U[i].dot(a_pre)) / data.D[i];
    data.a[i] = a_pre + data.S[i] * data.ddq[k];
  }
  return data.ddq;
}

}  // namespace wbi::model
