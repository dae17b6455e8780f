// Forward kinematics: body poses, joint motion axes, velocities.
#pragma once

#include <Eigen/Core>

#include "wbi/model/data.hpp"

namespace wbi::model {

// forward_kinematics — RBDA §4.1 (eqs. 4.1–4.3) in world coordinates:
//   R_WB[i] = R_WB[λ] R_PJ[i] R_J(q_i),  p_WB[i] = p_WB[λ] + R_WB[λ] p_PJ[i] + R_WB[λ] R_PJ[i]
//   p_J(q_i) S[i]    = motion axis of joint i in world axes at the world origin.
// Root: (p_WB, quaternion) from q for a floating base, identity for a fixed base.
// In:  q [nq] (checked, unit quaternion).  Writes: R_WB, p_WB, S.
void forward_kinematics(const Model& model, Data& data, const ConstVectorRef& q);

// forward_velocity_kinematics — forward_kinematics, then
//   v[0] = S_B ν_B,  a[0] = (ṗ_B × ω_B, 0)               (mixed base, ν̇ = 0)
//   v[i] = v[λ] + S_i q̇_i,  a[i] = a[λ] + v[i] × S_i q̇_i  (RBDA eq. 5.7 with q̈ = 0, no gravity)
// so a[i] is the bias (J̇ν) part of the spatial acceleration of body i.
// In: q [nq], nu [nv].  Writes: R_WB, p_WB, S, v, a.
void forward_velocity_kinematics(const Model& model, Data& data, const ConstVectorRef& q,
                                 const ConstVectorRef& nu);

// world_H_frame (4×4) of a frame. Pre: forward_kinematics current. Writes nothing.
Eigen::Matrix4d frame_pose(const Model& model, const Data& data, int frame);

}  // namespace wbi::model
