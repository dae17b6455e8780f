#include "wbi_backend.hpp"

#include "checks.hpp"
#include "wbi/model/algorithms.hpp"

namespace wbi::model {

namespace {

class WbiBackend final : public ModelBackend {
  // (first: their deduced return types are used below)
  // Every algorithm but frame_jacobian(q, frame) leaves the poses of all bodies at q
  // in data_: remembered so that frame queries at the same q skip the kinematics.
  // Invalid while the algorithm runs, so that one that throws leaves nothing stale.
  template <class Algorithm>
  const auto& all_bodies_at(const ConstVectorRef& q, Algorithm algorithm) {
    kinematics_valid_ = false;
    const auto& result = algorithm();
    kinematics_q_ = q;
    kinematics_valid_ = true;
    return result;
  }
  bool kinematics_current(const ConstVectorRef& q) const {
    return kinematics_valid_ && q.size() == kinematics_q_.size() && q == kinematics_q_;
  }

 public:
  explicit WbiBackend(Model model) : model_(std::move(model)), data_(model_) {}

  std::string_view name() const override { return "wbi"; }
  const Model& model() const override { return model_; }

  const Eigen::MatrixXd& mass_matrix(const ConstVectorRef& q) override {
    return all_bodies_at(
        q, [&]() -> const auto& { return wbi::model::mass_matrix(model_, data_, q); });
  }
  const Eigen::VectorXd& bias_forces(const ConstVectorRef& q, const ConstVectorRef& nu,
                                     const Vector3d& gravity) override {
    return all_bodies_at(
        q, [&]() -> const auto& { return wbi::model::bias_forces(model_, data_, q, nu, gravity); });
  }
  const Eigen::VectorXd& gravity_forces(const ConstVectorRef& q, const Vector3d& gravity) override {
    return all_bodies_at(
        q, [&]() -> const auto& { return wbi::model::gravity_forces(model_, data_, q, gravity); });
  }
  const Eigen::VectorXd& inverse_dynamics(const ConstVectorRef& q, const ConstVectorRef& nu,
                                          const ConstVectorRef& dnu, const Vector3d& gravity,
                                          std::span<const ExternalWrench> wrenches) override {
    return all_bodies_at(
        q, [&]() -> const auto& {
          return wbi::model::inverse_dynamics(model_, data_, q, nu, dnu, gravity, wrenches);
        });
  }
  const Eigen::VectorXd& forward_dynamics(const ConstVectorRef& q, const ConstVectorRef& nu,
                                          const ConstVectorRef& tau, const Vector3d& gravity,
                                          std::span<const ExternalWrench> wrenches) override {
    return all_bodies_at(
        q, [&]() -> const auto& {
          return wbi::model::forward_dynamics(model_, data_, q, nu, tau, gravity, wrenches);
        });
  }
  const Eigen::Matrix4d& frame_pose(const ConstVectorRef& q, int frame) override {
    backend_detail::check_frame(model_, frame);
    if (!kinematics_current(q)) {
      all_bodies_at(
          q, [&]() -> const auto& {
            forward_kinematics(model_, data_, q);
            return data_.R_WB;
          });
    }
    pose_ = wbi::model::frame_pose(model_, data_, frame);
    return pose_;
  }
  const Eigen::MatrixXd& frame_jacobian(const ConstVectorRef& q, int frame) override {
    backend_detail::check_frame(model_, frame);
    if (kinematics_current(q)) {
      return wbi::model::frame_jacobian(model_, data_, frame);
    }
    kinematics_valid_ = false;  // only the frame's support is updated to q
    return wbi::model::frame_jacobian(model_, data_, q, frame);
  }
  const Vector6d& frame_bias_acceleration(const ConstVectorRef& q, const ConstVectorRef& nu,
                                          int frame) override {
    backend_detail::check_frame(model_, frame);
    all_bodies_at(
        q, [&]() -> const auto& {
          forward_velocity_kinematics(model_, data_, q, nu);
          return data_.v;
        });
    return wbi::model::frame_bias_acceleration(model_, data_, frame);
  }
  const Vector3d& center_of_mass(const ConstVectorRef& q) override {
    return all_bodies_at(
        q, [&]() -> const auto& { return wbi::model::center_of_mass(model_, data_, q); });
  }
  const Eigen::MatrixXd& com_jacobian(const ConstVectorRef& q) override {
    return all_bodies_at(
        q, [&]() -> const auto& { return wbi::model::com_jacobian(model_, data_, q); });
  }
  const Vector6d& centroidal_momentum(const ConstVectorRef& q, const ConstVectorRef& nu) override {
    return all_bodies_at(
        q, [&]() -> const auto& { return wbi::model::centroidal_momentum(model_, data_, q, nu); });
  }
  const Eigen::MatrixXd& centroidal_momentum_matrix(const ConstVectorRef& q) override {
    return all_bodies_at(
        q, [&]() -> const auto& {
          return wbi::model::centroidal_momentum_matrix(model_, data_, q);
        });
  }

 private:
  const Model model_;
  Data data_;
  Eigen::Matrix4d pose_ = Eigen::Matrix4d::Identity();
  Eigen::VectorXd kinematics_q_ = Eigen::VectorXd::Zero(model_.nq);
  bool kinematics_valid_ = false;
};

}  // namespace

std::unique_ptr<ModelBackend> make_wbi_backend(const std::string& urdf,
                                               const LoadOptions& options) {
  return make_wbi_backend(load_urdf_file(urdf, options));
}

std::unique_ptr<ModelBackend> make_wbi_backend(Model model) {
  return std::make_unique<WbiBackend>(std::move(model));
}

}  // namespace wbi::model
