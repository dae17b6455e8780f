#include "wbi/model/rnea.hpp"

#include "../checks.hpp"
#include "../inertias.hpp"
#include "wbi/model/kinematics.hpp"

namespace wbi::model {

const Eigen::VectorXd& inverse_dynamics(const Model& model, Data& data, const ConstVectorRef& q,
                                        const ConstVectorRef& nu, const ConstVectorRef& dnu,
                                        const Vector3d& gravity,
                                        std::span<const ExternalWrench> wrenches) {
  detail::check_size("inverse_dynamics", "nu", nu, model.nv);
  detail::check_size("inverse_dynamics", "dnu", dnu, model.nv);
  for (const ExternalWrench& w : wrenches) {
    detail::check_frame(model, w.frame);
  }
  forward_kinematics(model, data, q);
  detail::world_inertias(model, data);
  // root: v_0 = S_B ν_B,  a_0 = S_B ν̇_B + (ṗ_B × ω_B, 0) − (g, 0)
  Vector6d a_g;
  a_g << -gravity, Vector3d::Zero();
  if (model.floating_base) {
    const Vector6d nu_B = nu.head<6>();
    data.v[0] = detail::base_motion(data.p_WB[0], nu_B);
    data.a[0] = detail::base_motion(data.p_WB[0], dnu.head<6>()) + a_g;
    data.a[0].head<3>() += nu_B.head<3>().cross(nu_B.tail<3>());
  } else {
    data.v[0].setZero();
    data.a[0] = a_g;
  }
  data.f[0] = data.I_W[0] * data.a[0] + cross_force(data.v[0], data.I_W[0] * data.v[0]);
  // out: v_i = v_λ + S q̇,  a_i = a_λ + S q̈ + v_i × S q̇,  f_i = I a_i + v_i ×* I v_i
  for (int i = 1; i < model.n_bodies; ++i) {
    const int lambda = model.parent[i];
    const int k = model.body_v_index[i];
    // In locals, stored once: reading v_i, a_i back from Data right after storing them
    // made clang 14 load 3-vector halves across two 16-byte stores (a store-forwarding
    // stall on every cross product).
    const Vector6d& S = data.S[i];
    const Vector6d vJ = S * nu[k];
    const Vector6d v = data.v[lambda] + vJ;
    const Vector6d a = data.a[lambda] + S * dnu[k] + cross_motion(v, vJ);
    const SpatialInertia& I = data.I_W[i];
    data.f[i] = I * a + cross_force(v, I * v);
    data.v[i] = v;
    data.a[i] = a;
  }
  // external wrenches: (f, n_F) at p_F → (f, n_F + p_F × f) at the world origin
  for (const ExternalWrench& w : wrenches) {
    const int b = model.frame_body[w.frame];
    const Vector3d p_F = data.p_WB[b] + data.R_WB[b] * model.frame_p_BF[w.frame];
    data.f[b].head<3>() -= w.wrench.head<3>();
    data.f[b].tail<3>() -= w.wrench.tail<3>() + p_F.cross(w.wrench.head<3>());
  }
  // back: τ_i = S_iᵀ f_i,  f_λ += f_i
  for (int i = model.n_bodies - 1; i > 0; --i) {
    data.tau[model.body_v_index[i]] = data.S[i].dot(data.f[i]);
    data.f[model.parent[i]] += data.f[i];
  }
  if (model.floating_base) {
    data.tau.head<6>() = detail::base_force(data.p_WB[0], data.f[0]);
  }
  // armature: τ_k += armature_k q̈_k, no velocity term (model.hpp); skipped where zero
  for (int k = 0; k < model.n_joints; ++k) {
    if (model.joint_armature[k] != 0.0) {
      data.tau[model.base_nv + k] += model.joint_armature[k] * dnu[model.base_nv + k];
    }
  }
  return data.tau;
}

const Eigen::VectorXd& bias_forces(const Model& model, Data& data, const ConstVectorRef& q,
                                   const ConstVectorRef& nu, const Vector3d& gravity) {
  detail::check_size("bias_forces", "nu", nu, model.nv);
  // ν̇ = 0: a zero vector held in data.h itself (it is overwritten by the result)
  data.h.setZero();
  inverse_dynamics(model, data, q, nu, data.h, gravity);
  data.h = data.tau;
  return data.h;
}

const Eigen::VectorXd& gravity_forces(const Model& model, Data& data, const ConstVectorRef& q,
                                      const Vector3d& gravity) {
  forward_kinematics(model, data, q);
  detail::composite_mass_moments(model, data);
  // f_C[i] = (−m_C g, −h_C × g);  G_i = S_iᵀ f_C[i]
  for (int i = 1; i < model.n_bodies; ++i) {
    const Vector6d& S = data.S[i];
    const SpatialInertia& Ic = data.I_C[i];
    data.g[model.body_v_index[i]] =
        -Ic.m * S.head<3>().dot(gravity) - S.tail<3>().dot(Ic.h.cross(gravity));
  }
  if (model.floating_base) {
    Vector6d f0;
    f0 << -data.I_C[0].m * gravity, -data.I_C[0].h.cross(gravity);
    data.g.head<6>() = detail::base_force(data.p_WB[0], f0);
  }
  return data.g;
}

}  // namespace wbi::model
