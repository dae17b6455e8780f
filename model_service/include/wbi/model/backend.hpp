// A model backend: the Model element's operations computed by one dynamics
// library. The controller-facing code (model service, proxy, `wbi model`) talks
// to this interface only, so the library behind it is chosen by configuration:
//   "wbi"   the project's own library (wbi::model), the default
//   "dart"  DART 6 (built when DART is installed, see model_service/README.md)
//
// Every backend answers in the conventions of docs/conventions.md: q and ν in
// the layout of model() (floating base (p_WB, quaternion w,x,y,z, s) and mixed
// ν = (ṗ_B, ω_B, ṡ), world axes; joints in model().joint_name order), 6D
// vectors linear first. The layout, the frames and the limits always come
// from wbi's own URDF loader (model()), so both backends index alike.
//
// Each call takes the whole state it needs and returns a reference to a buffer
// of the backend, valid until the next call. Sizes are checked (std::invalid_argument
// naming the argument). No allocation per call after construction, except
// where a backend documents it (model_service/README.md). One backend per thread.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "wbi/model/data.hpp"
#include "wbi/model/model.hpp"
#include "wbi/model/urdf.hpp"

namespace wbi::model {

class ModelBackend {
 public:
  virtual ~ModelBackend() = default;
  ModelBackend(const ModelBackend&) = delete;
  ModelBackend& operator=(const ModelBackend&) = delete;

  // "wbi" or "dart".
  virtual std::string_view name() const = 0;
  // Layout of q and ν, joints, frames, limits (wbi's loader, same options).
  virtual const Model& model() const = 0;

  // M(q) [nv×nv].
  virtual const Eigen::MatrixXd& mass_matrix(const ConstVectorRef& q) = 0;
  // h = C(q,ν)ν + G(q) [nv].
  virtual const Eigen::VectorXd& bias_forces(const ConstVectorRef& q, const ConstVectorRef& nu,
                                             const Vector3d& gravity) = 0;
  // G(q) [nv].
  virtual const Eigen::VectorXd& gravity_forces(const ConstVectorRef& q,
                                                const Vector3d& gravity) = 0;
  // τ = M ν̇ + h − Σ J_Fᵀ w_F [nv].
  virtual const Eigen::VectorXd& inverse_dynamics(
      const ConstVectorRef& q, const ConstVectorRef& nu, const ConstVectorRef& dnu,
      const Vector3d& gravity, std::span<const ExternalWrench> wrenches = {}) = 0;
  // ν̇ = M⁻¹(τ + Σ J_Fᵀ w_F − h) [nv].
  virtual const Eigen::VectorXd& forward_dynamics(
      const ConstVectorRef& q, const ConstVectorRef& nu, const ConstVectorRef& tau,
      const Vector3d& gravity, std::span<const ExternalWrench> wrenches = {}) = 0;
  // world_H_frame (4×4).
  virtual const Eigen::Matrix4d& frame_pose(const ConstVectorRef& q, int frame) = 0;
  // J_F [6×nv]: ν → (ṗ_F, ω_F) at the frame origin, world axes.
  virtual const Eigen::MatrixXd& frame_jacobian(const ConstVectorRef& q, int frame) = 0;
  // J̇_F ν [6].
  virtual const Vector6d& frame_bias_acceleration(const ConstVectorRef& q, const ConstVectorRef& nu,
                                                  int frame) = 0;
  // c [3], J_com [3×nv]; throw when the model has no mass.
  virtual const Vector3d& center_of_mass(const ConstVectorRef& q) = 0;
  virtual const Eigen::MatrixXd& com_jacobian(const ConstVectorRef& q) = 0;
  // h_G = (L, K_G) [6] and A_G [6×nv], world axes, angular part about the CoM.
  virtual const Vector6d& centroidal_momentum(const ConstVectorRef& q,
                                              const ConstVectorRef& nu) = 0;
  virtual const Eigen::MatrixXd& centroidal_momentum_matrix(const ConstVectorRef& q) = 0;

 protected:
  ModelBackend() = default;
};

// The names make_model_backend accepts in this build ("wbi", and "dart" when
// DART was found at configure time), sorted.
std::vector<std::string> model_backend_names();

// Throws std::invalid_argument naming name and the available backends unless
// make_model_backend accepts it (for checking a configuration before loading).
void check_model_backend_name(std::string_view name);

// Loads urdf (a file path) with options into the named backend. Throws
// std::invalid_argument for an unknown or unavailable name (listing the
// available ones) and std::runtime_error naming the file when it does not load.
std::unique_ptr<ModelBackend> make_model_backend(std::string_view name, const std::string& urdf,
                                                 const LoadOptions& options = {});

// The "wbi" backend on a model already loaded (copied into the backend).
std::unique_ptr<ModelBackend> make_wbi_backend(Model model);

}  // namespace wbi::model
