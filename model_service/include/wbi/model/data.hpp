// The workspace of the algorithms: every buffer is sized once here, from the
// Model, so that no algorithm allocates. One Data per thread; a Data may only
// be used with the Model it was built from.
//
// Spatial quantities are in world axes about the world origin, 6D vectors
// linear first (spatial.hpp). Fields are grouped by stage; each says its shape
// and which function writes it.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "wbi/model/model.hpp"
#include "wbi/model/spatial.hpp"

namespace wbi::model {

// Read-only view of q, ν, ν̇ or τ: binds to an Eigen::VectorXd or a segment without copying.
using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;

struct Data {
  explicit Data(const Model& model);

  // ---- position stage: forward_kinematics() ----
  std::vector<Matrix3d> R_WB;  // [n_bodies] rotation of body i in the world
  std::vector<Vector3d> p_WB;  // [n_bodies] origin of body i in the world
  std::vector<Vector6d> S;   // [n_bodies] motion axis of the joint of body i, world, entry 0 unused
  std::vector<int> support;  // [n_bodies] frame_jacobian(q): bodies from the frame body to the root

  // ---- inertias: world_inertias() (rnea, aba, centroidal_momentum), composite_inertias() ----
  std::vector<SpatialInertia> I_W;  // [n_bodies] body inertia, world axes about world origin
  std::vector<SpatialInertia>
      I_C;  // [n_bodies] composite inertia of the subtree (crba, centroidal, com)
  Eigen::Matrix<double, 6, Eigen::Dynamic> F;  // [6×n_bodies] crba: I_C[j] S_j (col 0 unused)

  // ---- velocity / acceleration stage: forward_velocity_kinematics(), rnea, aba ----
  std::vector<Vector6d> v;  // [n_bodies] spatial velocity of body i
  std::vector<Vector6d>
      a;  // [n_bodies] spatial acceleration (fvk: bias part with ν̇ = 0, no gravity;
          //            rnea/aba: full, gravity included as a_0 = (−g, 0))
  std::vector<Vector6d>
      f;  // [n_bodies] rnea: force transmitted by the joint of body i (subtree sum)

  // ---- articulated-body stage: forward_dynamics() ----
  std::vector<Matrix6d> IA;  // [n_bodies] articulated inertia
  std::vector<Vector6d> pA;  // [n_bodies] articulated bias force
  std::vector<Vector6d> c;   // [n_bodies] velocity-product acceleration v_i × S_i q̇_i
  std::vector<Vector6d> U;   // [n_bodies] IA_i S_i
  std::vector<double> D;     // [n_bodies] S_iᵀ U_i
  std::vector<double> u;     // [n_bodies] τ_i − S_iᵀ pA_i

  // ---- outputs ----
  Eigen::MatrixXd M;      // [nv×nv] mass matrix, symmetric: mass_matrix()
  Eigen::VectorXd tau;    // [nv] inverse_dynamics()
  Eigen::VectorXd h;      // [nv] bias forces C(q,ν)ν + G(q): bias_forces()
  Eigen::VectorXd g;      // [nv] gravity forces G(q): gravity_forces()
  Eigen::VectorXd ddq;    // [nv] ν̇: forward_dynamics()
  Eigen::MatrixXd J;      // [6×nv] frame Jacobian (ṗ_F, ω_F), world axes: frame_jacobian()
  Vector6d dJnu;          // [6] J̇ν of a frame: frame_bias_acceleration()
  Eigen::MatrixXd Ag;     // [6×nv] centroidal momentum matrix: centroidal_momentum_matrix()
  Vector6d hg;            // [6] centroidal momentum (L, K_G), world axes: centroidal_momentum()
  Vector3d com;           // [3] centre of mass in the world: center_of_mass(), com_jacobian(), …
  Eigen::MatrixXd J_com;  // [3×nv] CoM Jacobian: com_jacobian()
  Vector3d dJnu_com;      // [3] J̇_com ν: com_bias_acceleration()
};

// A wrench applied at a frame's origin: (force, moment about the frame origin),
// world axes, linear first.
struct ExternalWrench {
  int frame = 0;
  Vector6d wrench = Vector6d::Zero();
};

}  // namespace wbi::model
