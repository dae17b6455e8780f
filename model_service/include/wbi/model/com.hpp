// Centre of mass.
#pragma once

#include "wbi/model/data.hpp"

namespace wbi::model {

// center_of_mass — c = Σ m_i c_i / Σ m_i, world.  In: q [nq].
// Writes: R_WB, p_WB, S, com. Throws when the model has no mass.
const Vector3d& center_of_mass(const Model& model, Data& data, const ConstVectorRef& q);

// com_jacobian — J_com [3×nv] with J_com ν = ċ: linear rows of the centroidal
// momentum matrix over the mass, (m_j S_j,lin − h_C[j] × S_j,ang)/m per joint.
// In: q [nq].  Writes: R_WB, p_WB, S, I_C (m and h), com, J_com.
const Eigen::MatrixXd& com_jacobian(const Model& model, Data& data, const ConstVectorRef& q);

// com_bias_acceleration — J̇_com ν [3] = c̈ at ν̇ = 0 = Σ m_i (a_O + ω̇ × c_i + ω × ċ_i)/m.
// In: q [nq], nu [nv].  Writes: R_WB, p_WB, S, v, a, com, dJnu_com.
const Vector3d& com_bias_acceleration(const Model& model, Data& data, const ConstVectorRef& q,
                                      const ConstVectorRef& nu);

}  // namespace wbi::model
