#include "accelerations_from_model.hpp"

#include "base_from_state.hpp"

namespace wbi::estimator::detail {

namespace {

std::vector<int> contact_frames(const estimation::WrenchEstimator* wrenches,
                                std::vector<int>& hypotheses) {
  std::vector<int> frames;
  if (wrenches == nullptr) {
    return frames;
  }
  const auto links = wrenches->link_wrenches();
  for (std::size_t h = 0; h < links.size(); ++h) {
    if (wrenches->is_contact_link(static_cast<int>(h))) {
      hypotheses.push_back(static_cast<int>(h));
      frames.push_back(links[h].frame);
    }
  }
  return frames;
}

}  // namespace

AccelerationsFromModel::AccelerationsFromModel(model::Model model, estimation::JointLosses losses,
                                               const estimation::WrenchEstimator* wrenches)
    : wrenches_(wrenches) {
  auto frames = contact_frames(wrenches, contact_hypotheses_);
  held_.assign(contact_hypotheses_.size(), 0);
  q_model_.setZero(model.nq);
  if (model.floating_base) {
    q_model_[3] = 1.0;  // identity orientation (w first) until a state gives one
  }
  nu_.setZero(model.nv);
  tau_.setZero(model.n_joints);
  torque_known_.assign(static_cast<std::size_t>(model.n_joints), 0);
  accelerations_ = std::make_unique<estimation::ModelAccelerations>(
      std::move(model), std::move(losses), std::move(frames));
}

void AccelerationsFromModel::on_command(const wbi::msg::ActuatorCommand& command) {
  const auto& joints = command.joints();
  if (command.modes().size() != joints.size() || command.references().size() != joints.size()) {
    return;
  }
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const int j = joints[i];
    if (j >= tau_.size()) {
      continue;
    }
    const bool torque = command.modes()[i] == wbi::msg::ControlMode::TORQUE;
    auto& known = torque_known_[static_cast<std::size_t>(j)];
    known_ += static_cast<int>(torque) - static_cast<int>(known);
    known = torque ? 1 : 0;
    tau_[j] = torque ? command.references()[i] : 0.0;
  }
}

bool AccelerationsFromModel::compute(const Eigen::Ref<const Eigen::VectorXd>& q,
                                     const Eigen::VectorXd& dq,
                                     const wbi::msg::StateEstimate& state, Eigen::VectorXd& ddq) {
  const model::Model& m = accelerations_->model();
  if (known_ < m.n_joints) {
    return false;
  }
  if (m.floating_base) {
    base_from_state(state, q_model_, nu_);
  }
  q_model_.tail(m.n_joints) = q;
  nu_.tail(m.n_joints) = dq;
  for (std::size_t c = 0; c < contact_hypotheses_.size(); ++c) {
    held_[c] = wrenches_->loaded(contact_hypotheses_[c]) ? 1 : 0;
  }
  ddq = accelerations_->update(q_model_, nu_, tau_, held_).tail(m.n_joints);
  return true;
}

std::string AccelerationsFromModel::joints_without_torque() const {
  const model::Model& m = accelerations_->model();
  std::string names;
  for (int j = 0; j < m.n_joints; ++j) {
    if (torque_known_[static_cast<std::size_t>(j)] == 0) {
      names += (names.empty() ? "" : ", ") + m.joint_name[static_cast<std::size_t>(j)];
    }
  }
  return names;
}

}  // namespace wbi::estimator::detail
