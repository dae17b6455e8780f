// Vocabulary of the whole-body interface: joint lists, control modes, sensor
// and estimate kinds, read modes, stamps and errors.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <wbi/vocabulary/control_mode.hpp>
#include <wbi/vocabulary/sensor_kind.hpp>

namespace wbi {

// A list of joint (or sensor, or frame) names: the original WBI's IDList. The
// order of a controller's list is the order of every joint vector it reads or writes.
using IdList = std::vector<std::string>;

using VectorRef = Eigen::Ref<Eigen::VectorXd>;
using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;
using MatrixRef = Eigen::Ref<Eigen::MatrixXd>;
using Transform = Eigen::Matrix4d;  // homogeneous transform, e.g. world_H_base

// ControlMode: idle, position, position_direct, velocity, torque, pwm
// (wbi/vocabulary/control_mode.hpp).

// Low-level control parameters, per joint.
enum class ControlParameter { kp, ki, kd, reference_speed };

// SensorKind, what the Sensors element measures, and sensor_width(kind), the
// values per sensor of a kind: wbi/vocabulary/sensor_kind.hpp.

// What the State element estimates:
enum class EstimateKind {
  joint_position,      // 1 per controlled joint
  joint_velocity,      // 1 per controlled joint
  joint_acceleration,  // 1 per controlled joint
  joint_torque,        // 1 per controlled joint, filtered
  base_pose,           // 7: position [m], quaternion (w, x, y, z), world frame
  base_velocity,       // 6: mixed representation (ṗ_B, ω_B), world axes
  base_acceleration,   // 6: time derivative of base_velocity
  force_torque,        // 6 per F/T sensor, filtered
  external_wrench,     // 6 per link of State::external_wrench_links(): force [N], moment about
                       // the link origin [N m], world axes; estimated from F/T sensors
};

// Values per estimate of a kind (the counts above).
constexpr int estimate_width(EstimateKind kind) {
  switch (kind) {
    case EstimateKind::base_pose:
      return 7;
    case EstimateKind::base_velocity:
    case EstimateKind::base_acceleration:
    case EstimateKind::force_torque:
    case EstimateKind::external_wrench:
      return 6;
    default:
      return 1;
  }
}

// Estimates of a kind (the counts above), for a robot with `joints` controlled
// joints, `force_torque_sensors` F/T sensors and `external_wrench_links` links.
constexpr int estimate_count(EstimateKind kind, int joints, int force_torque_sensors,
                             int external_wrench_links = 0) {
  switch (kind) {
    case EstimateKind::base_pose:
    case EstimateKind::base_velocity:
    case EstimateKind::base_acceleration:
      return 1;
    case EstimateKind::force_torque:
      return force_torque_sensors;
    case EstimateKind::external_wrench:
      return external_wrench_links;
    default:
      return joints;
  }
}

enum class ReadMode {
  latest,    // the newest sample received (fails when older than the age limit)
  blocking,  // waits for a sample newer than the previous read of the same kind
};

// When and how fresh the data of a read is.
struct Stamp {
  std::int64_t source_ns = 0;  // source stamp of the sample (the robot's clock)
  std::uint64_t seq = 0;       // sequence number of the sample
  double age_s = 0.0;          // time since the sample arrived in this process
};

// One state estimate, whole: every field comes from the same sample (one
// stamp, one sequence number). Preallocate it once (or let the first
// State::read_robot_state size it) and read into it every tick.
struct RobotState {
  Eigen::VectorXd q;                               // [dofs] joint positions [rad or m]
  Eigen::VectorXd dq;                              // [dofs] joint velocities [rad/s or m/s]
  Eigen::VectorXd ddq;                             // [dofs] joint accelerations [rad/s^2 or m/s^2]
  Transform world_H_base = Transform::Identity();  // base pose
  Eigen::Matrix<double, 6, 1> base_velocity =      // (ṗ_B, ω_B), world axes (mixed)
      Eigen::Matrix<double, 6, 1>::Zero();
  Stamp stamp;  // of the one sample all fields come from

  RobotState() = default;
  explicit RobotState(int dofs)
      : q(Eigen::VectorXd::Zero(dofs)),
        dq(Eigen::VectorXd::Zero(dofs)),
        ddq(Eigen::VectorXd::Zero(dofs)) {}
};

// Any failure of the interface: names what was wrong.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A read found no data, or data older than the configured limit.
class StaleDataError : public Error {
 public:
  using Error::Error;
};

// A component did not answer in time (init, model requests, blocking reads).
class TimeoutError : public Error {
 public:
  using Error::Error;
};

}  // namespace wbi
