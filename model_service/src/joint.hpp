// Joint dispatch, in one place (STYLE.md rule 3). Every 1-DoF joint is a
// revolute or prismatic joint about a unit axis of its joint frame; no
// algorithm branches on the joint type.
#pragma once

#include <cmath>
#if defined(__GLIBC__)
#include <math.h>  // sincos (GNU)
#endif

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

// sin x and cos x from one call. g++ turns a std::sin, std::cos pair into one sincos
// call by itself; clang 14 cannot while errno is on (-fmath-errno, the default on
// Linux): it made two libm calls per joint, ~60 % of forward kinematics. glibc's
// sincos runs the same code as its sin and cos, so the results are the same bits.
inline void sin_cos(double x, double& s, double& c) {
#if defined(__GLIBC__)
  ::sincos(x, &s, &c);
#else
  s = std::sin(x);
  c = std::cos(x);
#endif
}

inline JointCalc joint_calc(JointType type, const Vector3d& axis, double q) {
  JointCalc j;
  if (type == JointType::kRevolute) {
    // Rodrigues: R = cos q 1 + sin q [a]× + (1 − cos q) a aᵀ
    double s, c;
    sin_cos(q, s, c);
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

// A joint about the coordinate axis ±e_K of its frame, R_WJ its frame's rotation in the
// world: columns K1, K2 rotate in their plane, S comes from column K. K is a template
// argument so that every column index is a constant: with a runtime k, R_WJ went
// through the stack and clang 14 reloaded its columns at run-time offsets.
// Rotations are read and written by columns only (3-vectors at 0, 24, 48 bytes): the
// next joint reads R_WB as its R_WP, and clang 14 copies a whole Matrix3d in 16-byte
// pieces at 0, 16, 32, 48, which straddle the column stores and cannot be forwarded
// from them (a store-forwarding stall per piece on every joint of a chain).
template <int K>
inline void joint_forward_axis(bool revolute, double sign, double q, const Vector3d& c_K,
                               const Vector3d& c_K1, const Vector3d& c_K2, Matrix3d& R_WB,
                               Vector3d& p_WB, Vector6d& S) {
  constexpr int K1 = (K + 1) % 3;
  constexpr int K2 = (K + 2) % 3;
  const Vector3d a_W = sign * c_K;
  if (revolute) {
    double s, c;
    sin_cos(sign * q, s, c);
    R_WB.col(K) = c_K;
    R_WB.col(K1) = c * c_K1 + s * c_K2;
    R_WB.col(K2) = c * c_K2 - s * c_K1;
    // Halves by fixed-size blocks, not `S << a, b`: the comma initializer copies
    // each 3-vector through a runtime-sized block, whose never-taken 4-wide AVX
    // path g++ 12 flags with -Warray-bounds (GCC PR 106247, Eigen #2506).
    S.head<3>() = p_WB.cross(a_W);
    S.tail<3>() = a_W;
  } else {
    R_WB.col(K) = c_K;
    R_WB.col(K1) = c_K1;
    R_WB.col(K2) = c_K2;
    p_WB += q * a_W;
    S.head<3>() = a_W;
    S.tail<3>().setZero();
  }
}

// The columns of R_WJ = R_WP R_PJ, each as R_WP times a column of R_PJ: no Matrix3d
// temporary, which clang 14 stored in other pieces than the columns read back.
template <int K>
inline void joint_forward_axis(const Model& model, int i, double q, const Matrix3d& R_WP,
                               Matrix3d& R_WB, Vector3d& p_WB, Vector6d& S) {
  constexpr int K1 = (K + 1) % 3;
  constexpr int K2 = (K + 2) % 3;
  const bool revolute = model.body_joint_type[i] == JointType::kRevolute;
  const double sign = model.body_joint_axis_sign[i];
  if (model.joint_R_PJ_identity[i]) {
    joint_forward_axis<K>(revolute, sign, q, R_WP.col(K), R_WP.col(K1), R_WP.col(K2), R_WB, p_WB,
                          S);
  } else {
    const Matrix3d& R_PJ = model.joint_R_PJ[i];
    joint_forward_axis<K>(revolute, sign, q, R_WP * R_PJ.col(K), R_WP * R_PJ.col(K1),
                          R_WP * R_PJ.col(K2), R_WB, p_WB, S);
  }
}

// The same joint, applied in world coordinates for forward kinematics (RBDA eq. 4.3):
//   R_WB = R_WP R_PJ R_J(q),  p_WB = p_WP + R_WP (p_PJ + R_PJ p_J(q)),  S_W = X_WB S_J.
// Coordinate axes (±e_k, the usual case in URDFs) rotate two columns only.
inline void joint_forward(const Model& model, int i, double q, const Matrix3d& R_WP,
                          const Vector3d& p_WP, Matrix3d& R_WB, Vector3d& p_WB, Vector6d& S) {
  p_WB.noalias() = p_WP + R_WP * model.joint_p_PJ[i];
  switch (model.body_joint_axis_index[i]) {
    case 0:
      joint_forward_axis<0>(model, i, q, R_WP, R_WB, p_WB, S);
      return;
    case 1:
      joint_forward_axis<1>(model, i, q, R_WP, R_WB, p_WB, S);
      return;
    case 2:
      joint_forward_axis<2>(model, i, q, R_WP, R_WB, p_WB, S);
      return;
    default:
      break;
  }
  Matrix3d R_WJ;
  if (model.joint_R_PJ_identity[i]) {
    R_WJ = R_WP;
  } else {
    R_WJ.noalias() = R_WP * model.joint_R_PJ[i];
  }
  const JointCalc jc = joint_calc(model.body_joint_type[i], model.body_joint_axis[i], q);
  p_WB.noalias() += R_WJ * jc.p;
  R_WB.noalias() = R_WJ * jc.R;
  S = motion_to_world(R_WB, p_WB, jc.S);
}

}  // namespace wbi::model::detail
