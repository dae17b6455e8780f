// Frame Jacobians in the mixed representation.
#pragma once

#include "wbi/model/data.hpp"

namespace wbi::model {

// frame_jacobian — J_F [6×nv] with J_F ν = (ṗ_F, ω_F), world axes, at the frame
// origin p_F (RBDA §4.4 eq. 4.29, columns S_k of the supporting joints, moved
// from the world origin to p_F: (s_O + ω_k × p_F, ω_k)). Base columns: [[1, −[p_F − p_B]×], [0,
// 1]]. Pre: forward_kinematics current.  Writes: J (columns outside the support are 0).
const Eigen::MatrixXd& frame_jacobian(const Model& model, Data& data, int frame);

// frame_jacobian from q — forward kinematics of the frame's supporting bodies
// only (root → frame body, RBDA eq. 4.3), then J as above. The poses of the other
// bodies in data are left as they were.
// In: q [nq].  Writes: R_WB, p_WB, S of the support bodies, support, J.
const Eigen::MatrixXd& frame_jacobian(const Model& model, Data& data, const ConstVectorRef& q,
                                      int frame);

// frame_bias_acceleration — J̇_F ν [6] = d/dt(ṗ_F, ω_F) at ν̇ = 0:
//   (a_O + ω̇ × p_F + ω × ṗ_F,  ω̇)   with (a_O, ω̇) = a[body], ṗ_F = v_O + ω × p_F.
// Pre: forward_velocity_kinematics current.  Writes: dJnu.
const Vector6d& frame_bias_acceleration(const Model& model, Data& data, int frame);

}  // namespace wbi::model
