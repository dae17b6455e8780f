#include "wbi/model/com.hpp"

#include <stdexcept>

#include "../checks.hpp"
#include "../inertias.hpp"
#include "wbi/model/kinematics.hpp"

namespace wbi::model {

namespace {
void check_mass(const Model& model) {
  if (!(model.total_mass > 0.0)) {
    throw std::invalid_argument("center of mass: model '" + model.name + "' has no mass");
  }
}
}  // namespace

const Vector3d& center_of_mass(const Model& model, Data& data, const ConstVectorRef& q) {
  check_mass(model);
  forward_kinematics(model, data, q);
  // c = Σ m_i (p_i + R_i c_i) / Σ m_i
  Vector3d mc = Vector3d::Zero();
  for (int i = 0; i < model.n_bodies; ++i) {
    mc += model.body_mass[i] * (data.p_WB[i] + data.R_WB[i] * model.body_com[i]);
  }
  data.com = mc / model.total_mass;
  return data.com;
}

const Eigen::MatrixXd& com_jacobian(const Model& model, Data& data, const ConstVectorRef& q) {
  check_mass(model);
  forward_kinematics(model, data, q);
  detail::composite_mass_moments(model, data);
  const double m = data.I_C[0].m;
  data.com = data.I_C[0].h / m;
  // joint column: (m_C S_lin − h_C × S_ang) / m  (linear momentum of the subtree per unit q̇)
  for (int j = 1; j < model.n_bodies; ++j) {
    const Vector6d& S = data.S[j];
    // a fixed-size 3×1 block: J_com's runtime-sized column draws g++ 12's -Warray-bounds
    // false positive with AVX (see joint.hpp)
    data.J_com.block<3, 1>(0, model.body_v_index[j]) =
        (data.I_C[j].m * S.head<3>() - data.I_C[j].h.cross(S.tail<3>())) / m;
  }
  // base: ċ = ṗ_B + ω_B × (c − p_B)
  if (model.floating_base) {
    data.J_com.leftCols<3>().setIdentity();
    data.J_com.middleCols<3>(3) = -skew(data.com - data.p_WB[0]);
  }
  return data.J_com;
}

const Vector3d& com_bias_acceleration(const Model& model, Data& data, const ConstVectorRef& q,
                                      const ConstVectorRef& nu) {
  check_mass(model);
  forward_velocity_kinematics(model, data, q, nu);
  // c̈ at ν̇ = 0:  Σ m_i (a_O + ω̇ × c_i + ω × ċ_i) / m,  ċ_i = v_O + ω × c_i
  Vector3d sum = Vector3d::Zero();
  Vector3d mc = Vector3d::Zero();
  for (int i = 0; i < model.n_bodies; ++i) {
    const double m = model.body_mass[i];
    const Vector3d c = data.p_WB[i] + data.R_WB[i] * model.body_com[i];
    const Vector3d omega = data.v[i].tail<3>();
    const Vector3d cdot = data.v[i].head<3>() + omega.cross(c);
    sum += m * (data.a[i].head<3>() + data.a[i].tail<3>().cross(c) + omega.cross(cdot));
    mc += m * c;
  }
  data.com = mc / model.total_mass;
  data.dJnu_com = sum / model.total_mass;
  return data.dJnu_com;
}

}  // namespace wbi::model
