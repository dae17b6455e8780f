#include "wbi/actuation/robot_backend.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace wbi::actuation {

int BackendDescription::joint_index(const std::string& name) const {
  for (std::size_t i = 0; i < joint_names.size(); ++i) {
    if (joint_names[i] == name) {
      return static_cast<int>(i);
    }
  }
  throw std::invalid_argument("robot '" + robot + "': unknown joint '" + name + "'");
}

bool BackendDescription::any_torque_sensor() const {
  return std::find(torque_sensor.begin(), torque_sensor.end(), true) != torque_sensor.end();
}

void SensorReadings::resize(const BackendDescription& description) {
  const auto n = static_cast<Eigen::Index>(description.n_joints());
  position = Eigen::VectorXd::Zero(n);
  velocity = Eigen::VectorXd::Zero(n);
  torque = Eigen::VectorXd::Zero(n);
  pwm = Eigen::VectorXd::Zero(n);
  imus.assign(description.imu_names.size(), ImuReading{});
  force_torque.assign(description.ft_names.size(), ForceTorqueReading{});
}

void JointCommands::resize(int n_joints) {
  mode.assign(static_cast<std::size_t>(n_joints), OutputMode::kIdle);
  value = Eigen::VectorXd::Zero(n_joints);
}

void JointCommands::set_idle() {
  for (auto& m : mode) {
    m = OutputMode::kIdle;
  }
  value.setZero();
}

namespace {
void require(LifecycleState actual, LifecycleState wanted, const char* what) {
  if (actual != wanted) {
    throw std::logic_error(std::string("robot backend: ") + what + " needs state " +
                           to_string(wanted) + ", the backend is " + to_string(actual));
  }
}
}  // namespace

void RobotBackend::configure() {
  require(state_, LifecycleState::unconfigured, "configure()");
  BackendDescription d = on_configure();
  const std::size_t n = d.joint_names.size();
  if (d.position_lower.size() != n || d.position_upper.size() != n ||
      d.velocity_limit.size() != n || d.effort_limit.size() != n ||
      !(d.position_kp.empty() || d.position_kp.size() == n) ||
      !(d.position_kd.empty() || d.position_kd.size() == n) ||
      !(d.torque_sensor.empty() || d.torque_sensor.size() == n) ||
      d.imu_frames.size() != d.imu_names.size() || d.ft_frames.size() != d.ft_names.size()) {
    throw std::logic_error("robot backend '" + d.robot +
                           "': on_configure() returned a description with inconsistent sizes");
  }
  if (d.torque_sensor.empty()) {
    d.torque_sensor.assign(n, true);  // a backend that says nothing: every joint has one
  }
  description_ = std::move(d);
  readings_.resize(description_);
  commands_.resize(description_.n_joints());
  idle_.resize(description_.n_joints());
  state_ = LifecycleState::inactive;
}

void RobotBackend::activate() {
  require(state_, LifecycleState::inactive, "activate()");
  on_activate();
  commands_.set_idle();
  state_ = LifecycleState::active;
}

void RobotBackend::deactivate() {
  require(state_, LifecycleState::active, "deactivate()");
  on_deactivate();
  commands_.set_idle();
  state_ = LifecycleState::inactive;
}

void RobotBackend::cleanup() {
  require(state_, LifecycleState::inactive, "cleanup()");
  on_cleanup();
  state_ = LifecycleState::unconfigured;
}

void RobotBackend::shutdown() {
  if (state_ == LifecycleState::finalized) {
    return;
  }
  if (state_ == LifecycleState::active) {
    on_deactivate();
    commands_.set_idle();
  }
  on_shutdown();
  state_ = LifecycleState::finalized;
}

void RobotBackend::read(Time time, Duration period) {
  if (state_ != LifecycleState::inactive && state_ != LifecycleState::active) {
    require(state_, LifecycleState::inactive, "read()");
  }
  on_read(time, period, readings_);
  for (std::size_t j = 0; j < description_.torque_sensor.size(); ++j) {
    if (!description_.torque_sensor[j]) {
      readings_.torque[static_cast<Eigen::Index>(j)] = std::numeric_limits<double>::quiet_NaN();
    }
  }
}

void RobotBackend::write(Time time, Duration period) {
  if (state_ == LifecycleState::active) {
    const auto n = static_cast<std::size_t>(description_.n_joints());
    if (commands_.mode.size() != n || static_cast<std::size_t>(commands_.value.size()) != n) {
      throw std::invalid_argument("robot backend '" + description_.robot +
                                  "': commands have the wrong size (expected " + std::to_string(n) +
                                  " joints)");
    }
    on_write(time, period, commands_);
    return;
  }
  require(state_, LifecycleState::inactive, "write()");
  on_write(time, period, idle_);
}

}  // namespace wbi::actuation
