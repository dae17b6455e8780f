// The URDF loader's checks of link masses and inertias, and the repair of a
// non-physical inertia (LoadOptions::repair_inertia).
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>

#include "urdf_detail.hpp"

namespace wbi::model::detail {

void check_inertial(const urdf::Link& link, bool strict, const Error& err) {
  if (!link.inertial) {
    return;
  }
  const urdf::Inertial& in = *link.inertial;
  const double m = in.mass;
  if (!std::isfinite(m) || m < 0.0) {
    err.fail("link '" + link.name + "' has a negative or non-finite mass (" + std::to_string(m) +
             ")");
  }
  Matrix3d I;
  I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  if (!I.allFinite()) {
    err.fail("link '" + link.name + "' has a non-finite inertia");
  }
  // always: no negative moment of inertia about the inertial axes
  if (I.diagonal().minCoeff() < 0.0) {
    std::ostringstream msg;
    msg << "link '" << link.name << "' has a non-physical inertia (negative moment: ixx " << in.ixx
        << ", iyy " << in.iyy << ", izz " << in.izz << ")";
    err.fail(msg.str());
  }
  if (!strict) {
    return;
  }
  // strict: positive semi-definite and triangle inequality λ1 + λ2 ≥ λ3
  const Vector3d e =
      Eigen::SelfAdjointEigenSolver<Matrix3d>(I, Eigen::EigenvaluesOnly).eigenvalues();
  const double tol = 1e-9 * std::max(1e-9, e.cwiseAbs().maxCoeff());
  if (e[0] < -tol || e[0] + e[1] < e[2] - tol) {
    std::ostringstream msg;
    msg << "link '" << link.name << "' has a non-physical inertia (principal moments " << e[0]
        << ", " << e[1] << ", " << e[2] << ")";
    err.fail(msg.str());
  }
}

// Inertia repair (LoadOptions::repair_inertia). A rotational inertia about the CoM
// is physical iff it is the inertia of some mass distribution: with principal
// moments λ_k, the second moments of mass along the principal axes,
// σ_k = (λ1 + λ2 + λ3)/2 − λ_k = ∫ x_k² dm, are all ≥ 0 (σ_k ≥ 0 is the triangle
// inequality λ_i + λ_j ≥ λ_k, and implies λ_k ≥ 0). The repair keeps the principal
// axes and raises each negative σ_k to kRepairFloor · Σσ (a flat but not
// infinitely thin body), which is the nearest valid inertia in the σ coordinates
// and strictly inside the valid set, so that MuJoCo's check (A + B ≥ C, no
// tolerance) also passes after rounding. Values σ_k ≥ −kRepairTolerance · Σσ
// count as valid (round-off of a body on the boundary, e.g. a thin plate).
constexpr double kRepairFloor = 1e-9;
constexpr double kRepairTolerance = 1e-12;

// Returns true and writes the repaired inertia when I is not physical.
bool repair_inertia(const Matrix3d& I, Matrix3d& repaired) {
  const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(I);
  const Vector3d lambda = eig.eigenvalues();
  const double s = 0.5 * lambda.sum();
  Vector3d sigma = Vector3d::Constant(s) - lambda;
  if (!(s > 0.0) || sigma.minCoeff() >= -kRepairTolerance * s) {
    return false;  // zero (massless or point mass) or physical
  }
  sigma = sigma.cwiseMax(kRepairFloor * s);
  const Vector3d moments = Vector3d::Constant(sigma.sum()) - sigma;  // λ'_k = Σσ' − σ'_k
  const Matrix3d V = eig.eigenvectors();
  repaired = V * moments.asDiagonal() * V.transpose();
  repaired = 0.5 * (repaired + repaired.transpose()).eval();
  return true;
}

}  // namespace wbi::model::detail
