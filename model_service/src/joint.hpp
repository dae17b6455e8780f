// Joint dispatch, in one place (STYLE.md rule 3). Every 1-DoF joint is a
// revolute or prismatic joint about a unit axis of its joint frame; no
// algorithm branches on the joint type.
#pragma once

#include <cmath>

#include "wbi/model/model.hpp"
#include "wbi/model/spatial.hpp"

namespace wbi::model::detail {

// X_J = (R, p): pose of the child (body) frame in the joint frame at position q;
// S: motion axis in the body frame (linear first). RBDA Table 4.1.
struct JointCalc {
  Matrix3d R;
  Vector3d p;
  Vector6d S;
};

inline JointCalc joint_calc(JointType type, const Vector3d& axis, double q) {
  JointCalc j;
  if (type == JointType::kRevolute) {
    // Rodrigues: R = cos q 1 + sin q [a]× + (1 − cos q) a aᵀ
    const double s = std::sin(q);
    const double c = std::cos(q);
    const double t = 1.0 - c;
    const double x = axis.x(), y = axis.y(), z = axis.z();
    j.R << c + t * x * x, t * x * y - s * z, t * x * z + s * y,  //
        t * x * y + s * z, c + t * y * y, t * y * z - s * x,     //
        t * x * z - s * y, t * y * z + s * x, c + t * z * z;
    j.p.setZero();
    j.S << 0.0, 0.0, 0.0, x, y, z;
  } else {
    j.R.setIdentity();
    j.p = axis * q;
    j.S << axis.x(), axis.y(), axis.z(), 0.0, 0.0, 0.0;
  }
  return j;
}

// The same joint, applied in world coordinates for forward kinematics (RBDA eq. 4.3):
//   R_WB = R_WP R_PJ R_J(q),  p_WB = p_WP + R_WP (p_PJ + R_PJ p_J(q)),  S_W = X_WB S_J.
// Coordinate axes (±e_k, the usual case in URDFs) rotate two columns only.
inline void joint_forward(const Model& model, int i, double q, const Matrix3d& R_WP,
                          const Vector3d& p_WP, Matrix3d& R_WB, Vector3d& p_WB, Vector6d& S) {
  Matrix3d R_WJ;
  if (model.joint_R_PJ_identity[i]) {
    R_WJ = R_WP;
  } else {
    R_WJ.noalias() = R_WP * model.joint_R_PJ[i];
  }
  p_WB.noalias() = p_WP + R_WP * model.joint_p_PJ[i];
  const int k = model.body_joint_axis_index[i];
  const double sign = model.body_joint_axis_sign[i];
  if (k >= 0) {
    // axis ±e_k: columns k1, k2 rotate in their plane; S from column k
    const int k1 = (k + 1) % 3;
    const int k2 = (k + 2) % 3;
    const Vector3d a_W = sign * R_WJ.col(k);
    if (model.body_joint_type[i] == JointType::kRevolute) {
      const double s = std::sin(sign * q);
      const double c = std::cos(sign * q);
      R_WB.col(k) = R_WJ.col(k);
      R_WB.col(k1) = c * R_WJ.col(k1) + s * R_WJ.col(k2);
      R_WB.col(k2) = c * R_WJ.col(k2) - s * R_WJ.col(k1);
      // Halves by fixed-size blocks, not `S << a, b`: the comma initializer copies
      // each 3-vector through a runtime-sized block, whose never-taken 4-wide AVX
      // path g++ 12 flags with -Warray-bounds (GCC PR 106247, Eigen #2506).
      S.head<3>() = p_WB.cross(a_W);
      S.tail<3>() = a_W;
    } else {
      R_WB = R_WJ;
      p_WB += q * a_W;
      S.head<3>() = a_W;
      S.tail<3>().setZero();
    }
    return;
  }
  const JointCalc jc = joint_calc(model.body_joint_type[i], model.body_joint_axis[i], q);
  p_WB.noalias() += R_WJ * jc.p;
  R_WB.noalias() = R_WJ * jc.R;
  S = motion_to_world(R_WB, p_WB, jc.S);
}

}  // namespace wbi::model::detail
