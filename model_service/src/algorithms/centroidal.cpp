#include "wbi/model/centroidal.hpp"

#include "../checks.hpp"
#include "../inertias.hpp"
#include "wbi/model/kinematics.hpp"

namespace wbi::model {

const Vector6d& centroidal_momentum(const Model& model, Data& data, const ConstVectorRef& q,
                                    const ConstVectorRef& nu) {
  forward_velocity_kinematics(model, data, q, nu);
  detail::world_inertias(model, data);
  // h_O = Σ_i I_W[i] v_i = (L, K_O) by halves (no Vector6d per body),  c = Σ h_i / Σ m_i
  Vector3d L = Vector3d::Zero();
  Vector3d K_O = Vector3d::Zero();
  double m = 0.0;
  Vector3d mc = Vector3d::Zero();
  for (int i = 0; i < model.n_bodies; ++i) {
    L += data.I_W[i].linear(data.v[i]);
    K_O += data.I_W[i].angular(data.v[i]);
    m += data.I_W[i].m;
    mc += data.I_W[i].h;
  }
  data.com = mc / m;
  data.hg = join(L, K_O - data.com.cross(L));  // K_G = K_O − c × L
  return data.hg;
}

const Eigen::MatrixXd& centroidal_momentum_matrix(const Model& model, Data& data,
                                                  const ConstVectorRef& q) {
  forward_kinematics(model, data, q);
  detail::composite_inertias(model, data);
  const SpatialInertia& I_tot = data.I_C[0];
  data.com = I_tot.h / I_tot.m;
  const Vector3d& p_B = data.p_WB[0];
  Eigen::MatrixXd& Ag = data.Ag;
  // joint columns: I_C[j] S_j, moment taken about the CoM, from 3-vector halves (no
  // Vector6d read back by halves) into a fixed-size block (Ag.col(k) has a runtime row
  // count, a copy that clang 14 made a memcpy call per column; two 3-blocks were 20 %
  // slower under g++ without -march=native)
  const Vector3d& com = data.com;
  for (int j = 1; j < model.n_bodies; ++j) {
    const int k = model.body_v_index[j];
    const Vector3d l = data.I_C[j].linear(data.S[j]);
    Ag.block<6, 1>(0, k) = join(l, data.I_C[j].angular(data.S[j]) - com.cross(l));
  }
  // base columns: I_C[0] S_B e_k, moment about the CoM
  if (model.floating_base) {
    for (int k = 0; k < 6; ++k) {
      Vector6d e = Vector6d::Zero();
      e[k] = 1.0;
      Ag.block<6, 1>(0, k) = force_at_point(I_tot * detail::base_motion(p_B, e), data.com);
    }
  }
  return Ag;
}

}  // namespace wbi::model
