#include "lab_posture.hpp"

#include <string>

namespace lab {

using wbi::controllers::kPerJoint;
using wbi::controllers::ParameterSpec;

std::vector<ParameterSpec> LabPosture::parameters() const {
  return {
      {.name = "target", .unit = "rad", .size = kPerJoint, .live = false},
      {.name = "sway_amplitude", .unit = "rad", .size = kPerJoint, .live = false, .optional = true},
      {.name = "start_s", .unit = "s", .default_value = {1.5}, .min = 0.0, .live = false},
      {.name = "move_s", .unit = "s", .default_value = {2.0}, .min = 1e-3, .live = false},
      {.name = "sway_frequency_hz",
       .unit = "Hz",
       .default_value = {0.5},
       .min = 1e-3,
       .live = false},
      {.name = "sway_periods", .default_value = {1.0}, .min = 0.0, .max = 100.0, .live = false}};
}

std::vector<wbi::controllers::ReferenceSpec> LabPosture::outputs() const {
  return {{.name = "posture", .unit = "rad", .help = "q_ref", .size = LabImpedance::kJoints}};
}

void LabPosture::configure(wbi::WholeBodyInterface& robot,
                           const wbi::controllers::ParameterTable& parameters) {
  const int n = robot.dofs();
  if (n != LabImpedance::kJoints) {
    throw wbi::Error(parameters.owner() + ": its posture output has " +
                     std::to_string(LabImpedance::kJoints) + " values, the host has " +
                     std::to_string(n) + " joints");
  }
  robot_ = &robot;
  state_ = wbi::RobotState(n);
  const auto values = [&](const char* name) {
    const auto v = parameters.values(parameters.index(name));
    return v.empty() ? Eigen::VectorXd::Zero(n).eval()
                     : Eigen::Map<const Eigen::VectorXd>(v.data(), n).eval();
  };
  trajectory_.target = values("target");
  trajectory_.sway = values("sway_amplitude");
  trajectory_.from = trajectory_.target;
  trajectory_.start_s = parameters.value(parameters.index("start_s"));
  trajectory_.move_s = parameters.value(parameters.index("move_s"));
  trajectory_.sway_hz = parameters.value(parameters.index("sway_frequency_hz"));
  trajectory_.sway_periods = static_cast<int>(parameters.value(parameters.index("sway_periods")));
  x_.setZero(n);
  v_.setZero(n);
  a_.setZero(n);
}

void LabPosture::activate(const wbi::RobotState& measured) {
  trajectory_.from = measured.q;  // from where the arm is
  start_ns_ = measured.stamp.source_ns;
  last_ns_ = -1;
}

// One point for this tick's state, at its stamp; none for a state answered already.
bool LabPosture::update(double /*time_s*/, double /*period_s*/) {
  robot_->state().read_robot_state(state_, wbi::ReadMode::latest);
  if (state_.stamp.source_ns == last_ns_) {
    return false;
  }
  last_ns_ = state_.stamp.source_ns;
  trajectory_.at(1e-9 * static_cast<double>(last_ns_ - start_ns_), x_, v_, a_);
  output_->write(last_ns_, {x_.data(), static_cast<std::size_t>(x_.size())},
                 {v_.data(), static_cast<std::size_t>(v_.size())},
                 {a_.data(), static_cast<std::size_t>(a_.size())});
  return true;
}

}  // namespace lab
