#include "wbi/model/kinematics.hpp"

#include <Eigen/Geometry>

#include "../checks.hpp"
#include "../joint.hpp"
#include "wbi/model/configuration.hpp"

namespace wbi::model {

void forward_kinematics(const Model& model, Data& data, const ConstVectorRef& q) {
  detail::check_data(model, data);
  check_configuration(model, q);
  // root: the base pose from q, or the world origin
  if (model.floating_base) {
    const Eigen::Quaterniond quat(q[3], q[4], q[5], q[6]);
    data.R_WB[0] = quat.normalized().toRotationMatrix();
    data.p_WB[0] = q.head<3>();
  } else {
    data.R_WB[0].setIdentity();
    data.p_WB[0].setZero();
  }
  // out from the root: X_WB[i] = X_WB[λ] X_PJ[i] X_J(q_i);  S[i] = X_WB[i] S_J
  for (int i = 1; i < model.n_bodies; ++i) {
    const int lambda = model.parent[i];
    detail::joint_forward(model, i, q[model.body_q_index[i]], data.R_WB[lambda], data.p_WB[lambda],
                          data.R_WB[i], data.p_WB[i], data.S[i]);
  }
}

void forward_velocity_kinematics(const Model& model, Data& data, const ConstVectorRef& q,
                                 const ConstVectorRef& nu) {
  detail::check_size("forward_velocity_kinematics", "nu", nu, model.nv);
  forward_kinematics(model, data, q);
  // root: v_0 = S_B ν_B, a_0 = Ṡ_B ν_B = (ṗ_B × ω_B, 0)
  if (model.floating_base) {
    const Vector6d nu_B = nu.head<6>();
    data.v[0] = detail::base_motion(data.p_WB[0], nu_B);
    // fixed-size halves, not `<<` (g++ 12 -Warray-bounds with AVX: see joint.hpp)
    data.a[0].head<3>() = nu_B.head<3>().cross(nu_B.tail<3>());
    data.a[0].tail<3>().setZero();
  } else {
    data.v[0].setZero();
    data.a[0].setZero();
  }
  // v_i = v_λ + S_i q̇_i,  a_i = a_λ + v_i × S_i q̇_i
  for (int i = 1; i < model.n_bodies; ++i) {
    const int lambda = model.parent[i];
    const Vector6d vJ = data.S[i] * nu[model.body_v_index[i]];
    data.v[i] = data.v[lambda] + vJ;
    data.a[i] = data.a[lambda] + cross_motion(data.v[i], vJ);
  }
}

Eigen::Matrix4d frame_pose(const Model& model, const Data& data, int frame) {
  detail::check_frame(model, frame);
  const int b = model.frame_body[frame];
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H.topLeftCorner<3, 3>() = data.R_WB[b] * model.frame_R_BF[frame];
  H.topRightCorner<3, 1>() = data.p_WB[b] + data.R_WB[b] * model.frame_p_BF[frame];
  return H;
}

}  // namespace wbi::model
