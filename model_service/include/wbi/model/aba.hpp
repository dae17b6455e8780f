// Forward dynamics by the articulated-body algorithm.
#pragma once

#include <span>

#include "wbi/model/data.hpp"

namespace wbi::model {

// forward_dynamics — ν̇ = M⁻¹(τ + Σ J_Fᵀ w_F − h), RBDA §7.3 (Table 7.1) in world
// coordinates (no transforms between bodies), gravity as a_0 = (−g, 0):
//   pass 1: v_i = v_λ + S_i q̇_i,  c_i = v_i × S_i q̇_i,  IA_i = I_W[i],  pA_i = v_i ×* I_W[i] v_i −
//   w_i pass 2 (leaves to root): U_i = IA_i S_i, D_i = S_iᵀ U_i, u_i = τ_i − S_iᵀ pA_i,
//           IA_λ += IA_i − U_i U_iᵀ / D_i,  pA_λ += pA_i + (IA_i − U_i U_iᵀ/D_i) c_i + U_i u_i /
//           D_i
//   base:   a_0 = IA_0⁻¹ (S_B⁻ᵀ τ_B − pA_0) (floating; 6×6 Cholesky), a_0 = (−g, 0) (fixed)
//           ν̇_B = S_B⁻¹ (a_0 + (g, 0) − (ṗ_B × ω_B, 0))
//   pass 3: q̈_i = (u_i − U_iᵀ (a_λ + c_i)) / D_i,  a_i = a_λ + c_i + S_i q̈_i.
// Pre: every body subtree behind a joint has non-zero inertia about that joint
// (D_i > 0); otherwise throws std::runtime_error naming the joint. In: q [nq], nu [nv], tau [nv],
// gravity [3], wrenches. Writes: R_WB, p_WB, S, I_W, v, a, c, IA, pA, U, D, u, ddq.
const Eigen::VectorXd& forward_dynamics(const Model& model, Data& data, const ConstVectorRef& q,
                                        const ConstVectorRef& nu, const ConstVectorRef& tau,
                                        const Vector3d& gravity,
                                        std::span<const ExternalWrench> wrenches = {});

}  // namespace wbi::model
