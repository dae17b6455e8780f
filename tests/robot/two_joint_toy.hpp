// The smallest robot a driver, an actuator side or a benchmark can run: two
// unit-inertia joints "a" and "b" (q̈ = τ), limits ±2 rad, 5 rad/s, 50 N·m.
#pragma once

#include <string>
#include <utility>

#include <Eigen/Core>
#include <wbi/actuation/robot_backend.hpp>

namespace wbi::test {

inline actuation::BackendDescription two_joint_description(const std::string& robot = "toy") {
  actuation::BackendDescription d;
  d.robot = robot;
  d.joint_names = {"a", "b"};
  d.position_lower = {-2.0, -2.0};
  d.position_upper = {2.0, 2.0};
  d.velocity_limit = {5.0, 5.0};
  d.effort_limit = {50.0, 50.0};
  return d;
}

// q̈ = τ per joint, integrated (semi-implicit Euler) when commands are written.
class TwoJointToyBackend final : public actuation::RobotBackend {
 public:
  explicit TwoJointToyBackend(std::string robot = "toy") : robot_(std::move(robot)) {}

 protected:
  actuation::BackendDescription on_configure() override { return two_joint_description(robot_); }
  void on_read(actuation::Time time, actuation::Duration, actuation::SensorReadings& out) override {
    out.position = q_;
    out.velocity = dq_;
    out.joint_stamp = time;
  }
  void on_write(actuation::Time, actuation::Duration period,
                const actuation::JointCommands& in) override {
    const double dt = 1e-9 * static_cast<double>(period.count());
    for (int i = 0; i < 2; ++i) {
      const bool torque = in.mode[static_cast<std::size_t>(i)] == actuation::OutputMode::kTorque;
      dq_[i] += (torque ? in.value[i] : 0.0) * dt;
      q_[i] += dq_[i] * dt;
    }
  }

 private:
  std::string robot_;
  Eigen::Vector2d q_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d dq_ = Eigen::Vector2d::Zero();
};

}  // namespace wbi::test
