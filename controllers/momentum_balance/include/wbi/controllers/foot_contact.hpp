// What a flat foot can take from the ground: its wrench (f, τ) about the sole
// frame's origin, in the sole frame, must satisfy rows · (f, τ) ≥ 0 (the
// first row ≥ a minimal normal force): unilateral, inside the inscribed
// friction pyramid, centre of pressure inside the support rectangle,
// torsional friction. Shared by the balancer and the walking controller.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace wbi::controllers {

inline constexpr int kFootConstraintRows = 11;

struct FootSupport {
  // The support rectangle in the sole frame [m]; it contains the origin.
  double x_min = -0.09, x_max = 0.09, y_min = -0.035, y_max = 0.035;
  double friction = 0.5;             // μ of the pyramid: |f_x|, |f_y| ≤ μ/√2 f_z
  double torsional_friction = 0.01;  // |τ_z| ≤ this × f_z [m]

  bool contains_origin() const { return x_min < 0.0 && x_max > 0.0 && y_min < 0.0 && y_max > 0.0; }
};

inline Eigen::Matrix<double, kFootConstraintRows, 6> foot_wrench_constraints(const FootSupport& s) {
  const double mu = s.friction / std::sqrt(2.0);
  const double mt = s.torsional_friction;
  Eigen::Matrix<double, kFootConstraintRows, 6> F;
  F.row(0) << 0, 0, 1, 0, 0, 0;          // f_z ≥ f_min
  F.row(1) << -1, 0, mu, 0, 0, 0;        // f_x ≤ μ' f_z
  F.row(2) << 1, 0, mu, 0, 0, 0;         // −f_x ≤ μ' f_z
  F.row(3) << 0, -1, mu, 0, 0, 0;        // f_y ≤ μ' f_z
  F.row(4) << 0, 1, mu, 0, 0, 0;         // −f_y ≤ μ' f_z
  F.row(5) << 0, 0, -s.x_min, 0, -1, 0;  // CoP_x = −τ_y / f_z ≥ x_min
  F.row(6) << 0, 0, s.x_max, 0, 1, 0;    // CoP_x ≤ x_max
  F.row(7) << 0, 0, -s.y_min, 1, 0, 0;   // CoP_y = τ_x / f_z ≥ y_min
  F.row(8) << 0, 0, s.y_max, -1, 0, 0;   // CoP_y ≤ y_max
  F.row(9) << 0, 0, mt, 0, 0, -1;        // τ_z ≤ μ_t f_z
  F.row(10) << 0, 0, mt, 0, 0, 1;        // −τ_z ≤ μ_t f_z
  return F;
}

// [v]× : [v]× w = v × w.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

}  // namespace wbi::controllers
