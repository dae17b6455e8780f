// Spatial (6D) algebra used by the model library.
//
// Convention (ARCHITECTURE.md): 6D vectors are LINEAR FIRST, then angular.
//   motion vector  v = (v_O, ω)  — v_O: velocity of the body point at the origin O
//                                   of the expression frame, ω: angular velocity
//   force vector   f = (f, n_O)  — force, moment about O
// RBDA (Featherstone 2008) writes them angular first; the formulas below are
// RBDA eqs. (2.31)-(2.35) with the two halves swapped.
// Inside the algorithms every spatial quantity is expressed in world axes at the
// world origin ("world frame" formulation, RBDA §2.9 / Pinocchio's oYcrb), so no
// 6×6 transform is ever formed.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wbi::model {

using Vector3d = Eigen::Vector3d;
using Matrix3d = Eigen::Matrix3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// [a]× b = a × b as a matrix.
inline Matrix3d skew(const Vector3d& a) {
  Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

// (lin, ang) as one 6D vector, written in three 16-byte pairs. The 6D results below
// are returned by value and usually copied on at once (into Data, F, J, …) in 16-byte
// pieces at 0, 16, 32. Filled as two 3-vector halves (16 + 8 bytes at 0 and 24),
// the pieces at 16 and 32 straddle two stores and cannot be forwarded from them:
// clang 14 kept such results on the stack and stalled on every copy (20 % of M's own
// loop). The comma initializer is no alternative: g++ 12 -Warray-bounds (Eigen #2506).
inline Vector6d join(const Vector3d& lin, const Vector3d& ang) {
  Vector6d r;
  r.segment<2>(0) = Eigen::Vector2d(lin.x(), lin.y());
  r.segment<2>(2) = Eigen::Vector2d(lin.z(), ang.x());
  r.segment<2>(4) = Eigen::Vector2d(ang.y(), ang.z());
  return r;
}

// v × m (motion cross product, RBDA eq. 2.31, linear first):
// (v, ω) × (u, w) = (ω × u + v × w, ω × w).
inline Vector6d cross_motion(const Vector6d& v, const Vector6d& m) {
  const Vector3d lin = v.tail<3>().cross(m.head<3>()) + v.head<3>().cross(m.tail<3>());
  const Vector3d ang = v.tail<3>().cross(m.tail<3>());
  return join(lin, ang);
}

// v ×* f (force cross product, RBDA eq. 2.32, linear first):
// (v, ω) ×* (f, n) = (ω × f, ω × n + v × f).
inline Vector6d cross_force(const Vector6d& v, const Vector6d& f) {
  const Vector3d lin = v.tail<3>().cross(f.head<3>());
  const Vector3d ang = v.tail<3>().cross(f.tail<3>()) + v.head<3>().cross(f.head<3>());
  return join(lin, ang);
}

// Spatial inertia about the origin O of its expression frame, 10 parameters:
//   m  mass, h = m c first moment of mass (c: centre of mass),
//   I  rotational inertia about O (not about the CoM): I = I_c + m [c]×ᵀ[c]×.
// As a 6×6 matrix (linear first): [[m 1, −[h]×], [[h]×, I]] (RBDA eq. 2.63, swapped).
// Composite inertias are plain sums of these parameters.
struct SpatialInertia {
  double m = 0.0;
  Vector3d h = Vector3d::Zero();
  Matrix3d I = Matrix3d::Zero();

  // Momentum I·v: (m v − h × ω, h × v + I ω).
  Vector6d operator*(const Vector6d& v) const { return join(linear(v), angular(v)); }
  // Its halves, for callers that go on with 3-vectors: the Vector6d in between costs a
  // round trip through memory whose pieces do not match (join).
  Vector3d linear(const Vector6d& v) const { return m * v.head<3>() - h.cross(v.tail<3>()); }
  Vector3d angular(const Vector6d& v) const { return h.cross(v.head<3>()) + I * v.tail<3>(); }
  SpatialInertia& operator+=(const SpatialInertia& o) {
    m += o.m;
    h += o.h;
    I += o.I;
    return *this;
  }
  Matrix6d matrix() const {
    Matrix6d r;
    const Matrix3d hx = skew(h);
    r.topLeftCorner<3, 3>() = m * Matrix3d::Identity();
    r.topRightCorner<3, 3>() = -hx;
    r.bottomLeftCorner<3, 3>() = hx;
    r.bottomRightCorner<3, 3>() = I;
    return r;
  }
  // From mass, CoM c and rotational inertia about the CoM I_c, all in the same axes.
  static SpatialInertia from_com(double mass, const Vector3d& c, const Matrix3d& I_c) {
    SpatialInertia r;
    r.m = mass;
    r.h = mass * c;
    r.I = I_c + mass * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose());
    return r;
  }
};

// Expresses a motion vector given in a frame with rotation R and origin p (world
// axes) in world axes at the world origin: (R v + p × R ω, R ω).
inline Vector6d motion_to_world(const Matrix3d& R, const Vector3d& p, const Vector6d& s) {
  const Vector3d ang = R * s.tail<3>();
  const Vector3d lin = R * s.head<3>() + p.cross(ang);
  return join(lin, ang);
}

// A world-origin motion (v_O, ω) seen at point p: (v_O + ω × p, ω).
inline Vector6d motion_at_point(const Vector6d& v, const Vector3d& p) {
  return join(v.head<3>() + v.tail<3>().cross(p), v.tail<3>());
}

// A world-origin force (f, n_O) as a moment about point p: (f, n_O − p × f).
inline Vector6d force_at_point(const Vector6d& f, const Vector3d& p) {
  return join(f.head<3>(), f.tail<3>() - p.cross(f.head<3>()));
}

}  // namespace wbi::model
