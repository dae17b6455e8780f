// What the DDS proxy needs from a model: the Model element's operations over
// the controlled joints (6 + dofs() generalized coordinates, base first),
// evaluated in-process (LocalModel) or by the robot's model service
// (RemoteModel). The proxy picks one from DdsInterfaceOptions::model_source.
#pragma once

#include <string>

#include "wbi/model.hpp"

namespace wbi::proxy {

class ModelBackend {
 public:
  virtual ~ModelBackend() = default;

  virtual const IdList& frames() const = 0;
  virtual int frame_index(const std::string& frame) const = 0;  // throws Error naming it
  virtual JointLimits joint_limits(int joint) const = 0;

  virtual void frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                          Transform& out) = 0;
  virtual void jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                        MatrixRef J) = 0;
  virtual void dj_nu(const ConstVectorRef& q, const Transform& world_H_base,
                     const ConstVectorRef& dq, const ConstVectorRef& base_velocity, int frame,
                     VectorRef out) = 0;
  virtual void mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) = 0;
  virtual void bias_forces(const ConstVectorRef& q, const Transform& world_H_base,
                           const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                           const Eigen::Vector3d& gravity, VectorRef h) = 0;
  virtual void gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                              const Eigen::Vector3d& gravity, VectorRef g) = 0;
  virtual void inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                                const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                const ConstVectorRef& ddq, const ConstVectorRef& base_acceleration,
                                const Eigen::Vector3d& gravity, VectorRef tau) = 0;
  virtual void centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                                   const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                   VectorRef out) = 0;
  virtual void centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                          MatrixRef A) = 0;
  virtual void com(const ConstVectorRef& q, const Transform& world_H_base,
                   Eigen::Vector3d& out) = 0;
  virtual void com_jacobian(const ConstVectorRef& q, const Transform& world_H_base,
                            MatrixRef J) = 0;
};

}  // namespace wbi::proxy
