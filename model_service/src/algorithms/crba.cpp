#include "wbi/model/crba.hpp"

#include "../checks.hpp"
#include "../inertias.hpp"
#include "wbi/model/kinematics.hpp"

namespace wbi::model {

const Eigen::MatrixXd& mass_matrix(const Model& model, Data& data, const ConstVectorRef& q) {
  forward_kinematics(model, data, q);
  detail::composite_inertias(model, data);
  Eigen::MatrixXd& M = data.M;
  auto& F = data.F;
  const int nb = model.base_nv;
  M.setZero();  // entries of joints on different branches are 0
  // F_j = I_C[j] S_j (world-origin force per unit q̇_j)
  for (int j = 1; j < model.n_bodies; ++j) {
    F.col(j) = data.I_C[j] * data.S[j];
  }
  // M_ij = S_iᵀ F_j for j in the subtree of i (bodies i … i + n − 1, contiguous by
  // construction). One fixed-size 6-dot per entry: the row as a 1×6 by 6×n product went
  // through Eigen's runtime-sized GEMV for a handful of columns (n is mostly 1 to 7).
  for (int i = 1; i < model.n_bodies; ++i) {
    const int n = model.body_subtree_size[i];
    const int vi = model.body_v_index[i];
    const Vector6d& S_i = data.S[i];
    for (int j = i; j < i + n; ++j) {
      const int vj = model.body_v_index[j];
      M(vi, vj) = M(vj, vi) = S_i.dot(F.col(j));
    }
  }
  if (nb == 6) {
    // base rows: S_Bᵀ F_j = (f, n_O − p_B × f); base block: S_Bᵀ I_C[0] S_B
    const Vector3d& p_B = data.p_WB[0];
    for (int j = 1; j < model.n_bodies; ++j) {
      const int vj = model.body_v_index[j];
      M.block<3, 1>(0, vj) = F.col(j).head<3>();
      M.block<3, 1>(3, vj) = F.col(j).tail<3>() - p_B.cross(F.col(j).head<3>());
    }
    Matrix6d M_BB;
    for (int k = 0; k < 6; ++k) {
      Vector6d e = Vector6d::Zero();
      e[k] = 1.0;
      M_BB.col(k) = detail::base_force(p_B, data.I_C[0] * detail::base_motion(p_B, e));
    }
    M.topLeftCorner<6, 6>() = 0.5 * (M_BB + M_BB.transpose());  // exactly symmetric
    M.block(nb, 0, model.n_joints, 6) = M.block(0, nb, 6, model.n_joints).transpose();
  }
  // armature: reflected rotor inertia on the diagonal of the joint block only (model.hpp);
  // skipped where zero so that a model without armature gives today's M bit for bit
  for (int k = 0; k < model.n_joints; ++k) {
    if (model.joint_armature[k] != 0.0) {
      M(nb + k, nb + k) += model.joint_armature[k];
    }
  }
  return M;
}

}  // namespace wbi::model
