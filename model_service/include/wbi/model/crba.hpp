// Mass matrix by the composite-rigid-body algorithm.
#pragma once

#include "wbi/model/data.hpp"

namespace wbi::model {

// mass_matrix — M(q) [nv×nv], RBDA §6.2 (Table 6.2) in world coordinates:
//   I_C[i] = I_W[i] + Σ_{children c} I_C[c]
//   M_ij = S_iᵀ I_C[j] S_j   for i an ancestor of j (or i = j), M_ji = M_ij
//   base rows: S_Bᵀ I_C[j] S_j with S_B = [[1, [p_B]×], [0, 1]] (mixed base velocity).
// Exploits sparsity: only the ancestors of j are visited. M is fully symmetric.
// In: q [nq].  Writes: R_WB, p_WB, S, I_W, I_C, M.
const Eigen::MatrixXd& mass_matrix(const Model& model, Data& data, const ConstVectorRef& q);

}  // namespace wbi::model
