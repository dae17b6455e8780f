#include "lab_impedance.hpp"

#include <cstdio>
#include <string>

namespace lab {

using wbi::controllers::ParameterSpec;
using wbi::controllers::ReferenceSpec;
using wbi::controllers::ReferenceStatus;

namespace {

const char* status_text(ReferenceStatus status) {
  switch (status) {
    case ReferenceStatus::fresh:
      return "fresh";
    case ReferenceStatus::stale:
      return "stale";
    case ReferenceStatus::missing:
      return "missing";
  }
  return "?";
}

}  // namespace

std::vector<ParameterSpec> LabImpedance::parameters() const {
  return {{.name = "stiffness",
           .unit = "N m/rad",
           .help = "K: joint stiffness about the posture, one per joint",
           .default_value = {50.0},
           .size = wbi::controllers::kPerJoint,
           .min = 0.0,
           .max = 2000.0},
          {.name = "damping",
           .unit = "N m s/rad",
           .help = "D: joint damping, one per joint",
           .default_value = {2.0},
           .size = wbi::controllers::kPerJoint,
           .min = 0.0,
           .max = 200.0,
           .live = false}};
}

std::vector<ReferenceSpec> LabImpedance::references() const {
  return {{.name = "posture",
           .unit = "rad",
           .help = "q_ref: the joint posture to hold, one per joint (the 7-joint arm)",
           .size = kJoints,
           .max_age_s = 0.05,
           .rule = wbi::controllers::StaleRule::hold_last}};
}

std::vector<std::string> LabImpedance::signal_names() const {
  return {"max_joint_error", "posture_fresh"};
}

void LabImpedance::bind_references(std::span<wbi::controllers::ReferenceInput* const> inputs) {
  posture_ = inputs[0];  // one per references() entry, in order
}

void LabImpedance::configure(wbi::WholeBodyInterface& robot,
                             const wbi::controllers::ParameterTable& parameters) {
  const int n = robot.dofs();
  if (n != kJoints) {
    throw wbi::Error(parameters.owner() + ": its posture input has " + std::to_string(kJoints) +
                     " values (the arm's joints); this host controls " + std::to_string(n) +
                     " joints");
  }
  robot_ = &robot;
  state_ = wbi::RobotState(n);
  k_.setZero(n);
  d_.setZero(n);
  g_.setZero(n + 6);
  error_.setZero(n);
  tau_.setZero(n);
  stiffness_index_ = parameters.index("stiffness");
  damping_index_ = parameters.index("damping");
  parameters_changed(parameters);
}

// Between two ticks (also while inactive): into the sized buffers, no allocation.
void LabImpedance::parameters_changed(const wbi::controllers::ParameterTable& parameters) {
  k_ = Eigen::Map<const Eigen::VectorXd>(parameters.values(stiffness_index_).data(), k_.size());
  d_ = Eigen::Map<const Eigen::VectorXd>(parameters.values(damping_index_).data(), d_.size());
}

void LabImpedance::activate(const wbi::RobotState& /*measured*/) {
  robot_->set_control_mode(wbi::ControlMode::torque);
  answered_ = false;
}

bool LabImpedance::update(double /*time_s*/, double /*period_s*/) {
  // A state older than max_age_s throws StaleDataError: the host skips the tick.
  const wbi::Stamp stamp = robot_->read_robot_state(state_, wbi::ReadMode::latest);
  if (answered_ && stamp.seq == last_seq_) {
    return false;  // this state was answered already
  }
  answered_ = true;
  last_seq_ = stamp.seq;

  // q_ref at the state's time; without a fresh point, the stale rule's (the
  // measured posture before any point came).
  posture_status_ =
      posture_->at(stamp.source_ns, [this]() -> const Eigen::VectorXd& { return state_.q; });
  const Eigen::VectorXd& q_ref = posture_->position();

  robot_->gravity_forces(state_.q, state_.world_H_base, Eigen::Vector3d(0.0, 0.0, -9.81), g_);
  error_ = q_ref - state_.q;
  tau_ = g_.tail(tau_.size()) + k_.cwiseProduct(error_) - d_.cwiseProduct(state_.dq);

  max_error_ = error_.cwiseAbs().maxCoeff();
  signals_ = {max_error_, posture_status_ == ReferenceStatus::fresh ? 1.0 : 0.0};
  return true;
}

void LabImpedance::progress(char* line, std::size_t size) const {
  std::snprintf(line, size,
                "lab_impedance: max joint error %.4f rad; stiffness %.4g to %.4g N m/rad; "
                "posture %s",
                max_error_, k_.minCoeff(), k_.maxCoeff(), status_text(posture_status_));
}

std::string LabImpedance::summary() const {
  char line[80];
  std::snprintf(line, sizeof line, "lab_impedance: final max joint error: %.6f rad", max_error_);
  return line;
}

}  // namespace lab
