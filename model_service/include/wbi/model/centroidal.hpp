// Centroidal momentum (Orin, Goswami, Lee 2013, "Centroidal dynamics of a humanoid robot").
#pragma once

#include "wbi/model/data.hpp"

namespace wbi::model {

// centroidal_momentum — h_G = (L, K_G) [6]: linear momentum and angular momentum
// about the CoM, world axes:  h_O = Σ_i I_W[i] v_i,  L = h_O.lin,  K_G = h_O.ang − c × L.
// In: q [nq], nu [nv].  Writes: R_WB, p_WB, S, v, a, I_W, com, hg.
const Vector6d& centroidal_momentum(const Model& model, Data& data, const ConstVectorRef& q,
                                    const ConstVectorRef& nu);

// centroidal_momentum_matrix — A_G [6×nv] with A_G ν = h_G (Orin et al. eq. 14):
//   column of joint j: I_C[j] S_j moved to the CoM, base columns: I_C[0] S_B moved to the CoM.
// In: q [nq].  Writes: R_WB, p_WB, S, I_W, I_C, com, Ag.
const Eigen::MatrixXd& centroidal_momentum_matrix(const Model& model, Data& data,
                                                  const ConstVectorRef& q);

}  // namespace wbi::model
