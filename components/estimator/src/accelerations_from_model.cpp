#include "accelerations_from_model.hpp"

#include <wbi/model/aba.hpp>

namespace wbi::estimator::detail {

AccelerationsFromModel::AccelerationsFromModel(model::Model model)
    : model_(std::move(model)), data_(model_) {
  q_model_.setZero(model_.nq);
  if (model_.floating_base) {
    q_model_[3] = 1.0;  // identity orientation (w first) until a state gives one
  }
  nu_.setZero(model_.nv);
  tau_.setZero(model_.nv);
  torque_known_.assign(static_cast<std::size_t>(model_.n_joints), 0);
}

void AccelerationsFromModel::on_command(const wbi::msg::ActuatorCommand& command) {
  const auto& joints = command.joints();
  if (command.modes().size() != joints.size() || command.references().size() != joints.size()) {
    ++malformed_commands_;
    return;
  }
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const int j = joints[i];
    if (j >= model_.n_joints) {
      ++malformed_commands_;
      continue;
    }
    const bool torque = command.modes()[i] == wbi::msg::ControlMode::TORQUE;
    auto& known = torque_known_[static_cast<std::size_t>(j)];
    known_ += static_cast<int>(torque) - static_cast<int>(known);
    known = torque ? 1 : 0;
    tau_[model_.base_nv + j] = torque ? command.references()[i] : 0.0;
  }
}

bool AccelerationsFromModel::compute(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                                     const wbi::msg::StateEstimate& state,
                                     std::span<const model::ExternalWrench> wrenches,
                                     Eigen::VectorXd& ddq) {
  if (known_ < model_.n_joints) {
    return false;
  }
  if (model_.floating_base) {
    const auto& pose = state.base_pose();
    q_model_.head<7>() << pose.position().x(), pose.position().y(), pose.position().z(),
        pose.orientation().w(), pose.orientation().x(), pose.orientation().y(),
        pose.orientation().z();
    nu_.head<6>() = Eigen::Map<const model::Vector6d>(state.base_velocity().data());
  }
  q_model_.tail(model_.n_joints) = q;
  nu_.tail(model_.n_joints) = dq;
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  const auto& dnu = model::forward_dynamics(model_, data_, q_model_, nu_, tau_, gravity, wrenches);
  ddq = dnu.tail(model_.n_joints);
  return true;
}

std::string AccelerationsFromModel::joints_without_torque() const {
  std::string names;
  for (int j = 0; j < model_.n_joints; ++j) {
    if (torque_known_[static_cast<std::size_t>(j)] == 0) {
      names += (names.empty() ? "" : ", ") + model_.joint_name[static_cast<std::size_t>(j)];
    }
  }
  return names;
}

}  // namespace wbi::estimator::detail
