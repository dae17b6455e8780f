// The Model element: kinematics and dynamics of the free-floating robot over
// the controlled joints,  M(q)ν̇ + h(q, ν) = Bτ + Σ Jᵀ f,  h = C(q, ν)ν + G(q).
//
// Conventions (docs/conventions.md): q are the controlled joints' positions
// (size dofs()); the base pose is an explicit argument (world_H_base); ν =
// (ṗ_B, ω_B, q̇) in the mixed representation, so every generalized vector and
// matrix has 6 + dofs() rows/columns, base first; 6D vectors are linear
// first. Joints of the robot outside the controlled list are held at their
// locked positions (see the implementation's options) with zero velocity.
#pragma once

#include <string>

#include "wbi/types.hpp"

namespace wbi {

struct JointLimits {
  double position_min;  // [rad or m]; -inf when none
  double position_max;
  double velocity_max;  // [rad/s]; +inf when none
  double effort_max;    // [N m]; +inf when none
};

class Model {
 public:
  virtual ~Model() = default;

  virtual int dofs() const = 0;                  // controlled joints
  virtual const IdList& joint_list() const = 0;  // controlled joints, in order
  virtual JointLimits joint_limits(int joint) const = 0;
  virtual const IdList& frame_list() const = 0;                 // every link and frame of the URDF
  virtual int frame_index(const std::string& frame) const = 0;  // throws Error naming it

  // world_H_frame of a frame (forward kinematics).
  virtual void frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                          Transform& world_H_frame) = 0;
  // 6 × (6 + dofs()) Jacobian of the frame origin's (linear, angular) velocity, world axes.
  virtual void jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                        MatrixRef J) = 0;
  // J̇ν of the frame (6).
  virtual void dj_nu(const ConstVectorRef& q, const Transform& world_H_base,
                     const ConstVectorRef& dq, const ConstVectorRef& base_velocity, int frame,
                     VectorRef dj_nu) = 0;
  // Mass matrix, (6 + dofs())², symmetric.
  virtual void mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) = 0;
  // h = C(q, ν)ν + G(q), 6 + dofs().
  virtual void bias_forces(const ConstVectorRef& q, const Transform& world_H_base,
                           const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                           const Eigen::Vector3d& gravity, VectorRef h) = 0;
  // G(q), 6 + dofs().
  virtual void gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                              const Eigen::Vector3d& gravity, VectorRef g) = 0;
  // Generalized forces for ν̇ = (base_acceleration, ddq), 6 + dofs().
  virtual void inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                                const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                const ConstVectorRef& ddq, const ConstVectorRef& base_acceleration,
                                const Eigen::Vector3d& gravity, VectorRef tau) = 0;
  // Centroidal momentum (linear, angular about the CoM, world axes), 6.
  virtual void centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                                   const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                   VectorRef momentum) = 0;
  // Centroidal momentum matrix, 6 × (6 + dofs()).
  virtual void centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                          MatrixRef A) = 0;
  // Centre of mass in the world (3) and its Jacobian, 3 × (6 + dofs()).
  virtual void com(const ConstVectorRef& q, const Transform& world_H_base,
                   Eigen::Vector3d& com) = 0;
  virtual void com_jacobian(const ConstVectorRef& q, const Transform& world_H_base,
                            MatrixRef J) = 0;
};

}  // namespace wbi
