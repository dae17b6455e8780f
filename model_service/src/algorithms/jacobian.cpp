#include "wbi/model/jacobian.hpp"

#include "../checks.hpp"
#include "../joint.hpp"
#include "wbi/model/configuration.hpp"

namespace wbi::model {

const Eigen::MatrixXd& frame_jacobian(const Model& model, Data& data, int frame) {
  detail::check_frame(model, frame);
  const int b = model.frame_body[frame];
  const Vector3d p_F = data.p_WB[b] + data.R_WB[b] * model.frame_p_BF[frame];
  Eigen::MatrixXd& J = data.J;
  J.setZero();
  // support of the frame: column k = S_k seen at p_F = (s_O + ω_k × p_F, ω_k)
  // Written as two fixed-size 3-blocks: J is 6 × nv with 6 known at run time only, and
  // J.col(k) = (a Vector6d) was a runtime-sized copy that clang 14 made a memcpy call.
  for (int i = b; i > 0; i = model.parent[i]) {
    const Vector6d& S = data.S[i];
    const int k = model.body_v_index[i];
    J.block<3, 1>(0, k) = S.head<3>() + S.tail<3>().cross(p_F);
    J.block<3, 1>(3, k) = S.tail<3>();
  }
  // base: ṗ_F = ṗ_B + ω_B × (p_F − p_B),  ω_F = ω_B
  if (model.floating_base) {
    J.topLeftCorner<3, 3>().setIdentity();
    J.block<3, 3>(0, 3) = -skew(p_F - data.p_WB[0]);
    J.block<3, 3>(3, 3).setIdentity();
  }
  return J;
}

const Eigen::MatrixXd& frame_jacobian(const Model& model, Data& data, const ConstVectorRef& q,
                                      int frame) {
  detail::check_data(model, data);
  check_configuration(model, q);
  detail::check_frame(model, frame);
  // the support, leaf first: support[0] = frame body, …, support[n − 1] = root
  int n = 0;
  for (int i = model.frame_body[frame]; i >= 0; i = model.parent[i]) {
    data.support[n++] = i;
  }
  if (model.floating_base) {
    const Eigen::Quaterniond quat(q[3], q[4], q[5], q[6]);
    data.R_WB[0] = quat.normalized().toRotationMatrix();
    data.p_WB[0] = q.head<3>();
  } else {
    data.R_WB[0].setIdentity();
    data.p_WB[0].setZero();
  }
  // out along the support: X_WB[i] = X_WB[λ] X_PJ[i] X_J(q_i)
  for (int k = n - 2; k >= 0; --k) {
    const int i = data.support[k];
    const int lambda = model.parent[i];
    detail::joint_forward(model, i, q[model.body_q_index[i]], data.R_WB[lambda], data.p_WB[lambda],
                          data.R_WB[i], data.p_WB[i], data.S[i]);
  }
  return frame_jacobian(model, data, frame);
}

const Vector6d& frame_bias_acceleration(const Model& model, Data& data, int frame) {
  detail::check_frame(model, frame);
  const int b = model.frame_body[frame];
  const Vector3d p_F = data.p_WB[b] + data.R_WB[b] * model.frame_p_BF[frame];
  const Vector3d omega = data.v[b].tail<3>();
  const Vector3d pdot_F = data.v[b].head<3>() + omega.cross(p_F);
  // d/dt(v_O + ω × p_F) = a_O + ω̇ × p_F + ω × ṗ_F
  data.dJnu.head<3>() = data.a[b].head<3>() + data.a[b].tail<3>().cross(p_F) + omega.cross(pdot_F);
  data.dJnu.tail<3>() = data.a[b].tail<3>();
  return data.dJnu;
}

}  // namespace wbi::model
