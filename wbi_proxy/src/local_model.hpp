// The Model element evaluated in-process by a model backend (wbi::model, or DART
// when chosen: wbi/model/backend.hpp), over a reduced model
// whose joints are exactly the controller's (the others locked), so no index
// mapping is needed per call. Outputs always have 6 + dofs() generalized
// coordinates; for a fixed-base robot the base rows and columns are zero.
#pragma once

#include <map>
#include <string>

#include <memory>

#include <wbi/model/backend.hpp>
#include <wbi/model/model.hpp>

#include "wbi/model.hpp"

namespace wbi::proxy {

class LocalModel final : public wbi::Model {
 public:
  // Throws Error naming the file, joint or backend when the model does not load.
  // backend: "wbi" or "dart" (wbi::model::model_backend_names()); armature by
  // joint name (wbi::model::LoadOptions::armature).
  LocalModel(const std::string& urdf, const IdList& joints,
             const std::map<std::string, double>& locked_positions,
             const std::string& backend = "wbi",
             const std::map<std::string, double>& armature = {});

  int dofs() const override { return model_.n_joints; }
  const IdList& joint_list() const override { return model_.joint_name; }
  const IdList& frame_list() const override { return model_.frame_name; }
  int frame_index(const std::string& frame) const override;
  JointLimits joint_limits(int joint) const override;

  void frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                  Transform& out) override;
  void jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                MatrixRef J) override;
  void dj_nu(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
             const ConstVectorRef& base_velocity, int frame, VectorRef out) override;
  void mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) override;
  void bias_forces(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
                   const ConstVectorRef& base_velocity, const Eigen::Vector3d& gravity,
                   VectorRef h) override;
  void gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                      const Eigen::Vector3d& gravity, VectorRef g) override;
  void inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                        const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                        const ConstVectorRef& ddq, const ConstVectorRef& base_acceleration,
                        const Eigen::Vector3d& gravity, VectorRef tau) override;
  void centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                           const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                           VectorRef out) override;
  void centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                  MatrixRef A) override;
  void com(const ConstVectorRef& q, const Transform& world_H_base, Eigen::Vector3d& out) override;
  void com_jacobian(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef J) override;

 private:
  // Fills q_ (and nu_ when velocities are given) from the interface's arguments.
  void set_position(const ConstVectorRef& q, const Transform& world_H_base);
  void set_velocity(const ConstVectorRef& dq, const ConstVectorRef& base_velocity);
  // Copies a model output with base_nv base columns into an output with 6.
  void expand_columns(const Eigen::MatrixXd& from, MatrixRef to, const char* what) const;
  void expand_vector(const Eigen::VectorXd& from, VectorRef to, const char* what) const;

  std::unique_ptr<wbi::model::ModelBackend> backend_;
  const wbi::model::Model& model_;  // backend_->model()
  Eigen::VectorXd q_;               // [nq] model configuration
  Eigen::VectorXd nu_;              // [nv] model velocity
  Eigen::VectorXd dnu_;             // [nv] model acceleration
  int offset_;  // 6 − base_nv: rows of the interface's vectors the model has not
};

}  // namespace wbi::proxy
