// Inverse dynamics by the recursive Newton–Euler algorithm.
#pragma once

#include <span>

#include "wbi/model/data.hpp"

namespace wbi::model {

// inverse_dynamics — τ = M(q)ν̇ + C(q,ν)ν + G(q) − Σ_F J_Fᵀ w_F, RBDA §5.3 (Table 5.1)
// in world coordinates, gravity as a fictitious base acceleration a_0 = (−g, 0):
//   v_i = v_λ + S_i q̇_i
//   a_i = a_λ + S_i q̈_i + v_i × S_i q̇_i
//   f_i = I_W[i] a_i + v_i ×* I_W[i] v_i − Σ wrenches on body i,   f_λ += f_i
//   τ_i = S_iᵀ f_i,   τ_B = S_Bᵀ f_0 (force, moment about p_B).
// Mixed base: v_0 = S_B ν_B, a_0 = S_B ν̇_B + (ṗ_B × ω_B, 0) − (g, 0).
// In: q [nq], nu [nv], dnu [nv], gravity [3] (e.g. (0,0,−9.81)), wrenches
// (force, moment about the frame origin, world axes).  Writes: R_WB, p_WB, S, I_W, v, a, f, tau.
const Eigen::VectorXd& inverse_dynamics(const Model& model, Data& data, const ConstVectorRef& q,
                                        const ConstVectorRef& nu, const ConstVectorRef& dnu,
                                        const Vector3d& gravity,
                                        std::span<const ExternalWrench> wrenches = {});

// bias_forces — h = C(q,ν)ν + G(q) = inverse_dynamics with ν̇ = 0.  Writes: as above and h.
const Eigen::VectorXd& bias_forces(const Model& model, Data& data, const ConstVectorRef& q,
                                   const ConstVectorRef& nu, const Vector3d& gravity);

// gravity_forces — G(q) = Σ_i J_iᵀ(−m_i g) over the body CoMs: with ν = ν̇ = 0 RNEA reduces to
//   f_i = Σ_{subtree} (−m g, −h × g)  (only mass and first moments are needed),  G_i = S_iᵀ f_i.
// In: q [nq], gravity [3].  Writes: R_WB, p_WB, S, I_C (m and h only), g.
const Eigen::VectorXd& gravity_forces(const Model& model, Data& data, const ConstVectorRef& q,
                                      const Vector3d& gravity);

}  // namespace wbi::model
