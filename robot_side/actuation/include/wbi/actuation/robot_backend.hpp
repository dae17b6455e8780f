// The robot backend interface: the one hardware abstraction that the sensor and
// actuator components drive. A real robot driver and the simulators (wbi::sim,
// through SimulationBackend) implement the same class; see
// robot_side/sim/README.md, "Writing a driver".
//
// Lifecycle (the states of ros2_control's hardware components):
//   UNCONFIGURED  constructed; no communication with the hardware.
//   INACTIVE      configure() succeeded: sizes are fixed, readings and commands are
//                 allocated, read() works (states readable), write() applies nothing
//                 (every joint is left IDLE, i.e. unpowered).
//   ACTIVE        activate() succeeded: powered; write() applies the commands.
//   FINALIZED     shutdown() done; ready to be destroyed.
//   configure: UNCONFIGURED → INACTIVE   activate: INACTIVE → ACTIVE
//   deactivate: ACTIVE → INACTIVE        cleanup: INACTIVE → UNCONFIGURED
//   shutdown: any → FINALIZED (deactivates first when ACTIVE)
// (the same states and transitions as wbi::runtime::Component).
// A hook that throws leaves the state unchanged; the exception (a clear message)
// reaches the caller. Calling a transition or read/write in the wrong state
// throws std::logic_error.
//
// The control loop of the owner is, once per period:
//   backend.read(t, period);             // fills backend.readings()
//   controller.update(t, period, backend.readings(), backend.commands());
//   backend.write(t, period);            // applies backend.commands()
// read() and write() never allocate: every buffer is sized at configure().
//
// Copy and move are deleted: a device has one owner.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <wbi/vocabulary/lifecycle_state.hpp>

namespace wbi::actuation {

using Time = std::chrono::nanoseconds;      // time since the clock's epoch
using Duration = std::chrono::nanoseconds;  // a period

using Vector3d = Eigen::Vector3d;
using Vector4d = Eigen::Vector4d;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// States: wbi::LifecycleState (wbi/vocabulary/lifecycle_state.hpp).

// One inertial measurement unit, in the IMU frame's axes.
struct ImuReading {
  Vector4d orientation{1.0, 0.0, 0.0,
                       0.0};          // IMU frame in the world (R_WI), unit quaternion (w, x, y, z)
  Vector3d gyro = Vector3d::Zero();   // angular velocity [rad/s], IMU axes
  Vector3d accel = Vector3d::Zero();  // proper acceleration p̈ − g [m/s²], IMU axes
                                      // (at rest, level: (0, 0, +9.81))
  Time stamp{0};                      // source stamp of the sample
};

// One 6-axis force/torque sensor: (force [N], torque [N·m] about the sensor
// origin), both in the sensor frame's axes, linear first. Convention: the wrench
// the child side exerts on the parent side (wbi::msg::ForceTorqueReading).
struct ForceTorqueReading {
  Vector6d wrench = Vector6d::Zero();
  Time stamp{0};
};

// What the hardware offers, fixed at configure(). The joint order is the order
// of every per-joint vector below.
struct BackendDescription {
  std::string robot;
  std::string urdf;            // the robot's URDF file when the backend knows it, else ""
  bool floating_base = false;  // free-floating base (humanoid) or fixed to the world (arm)
  std::vector<std::string> joint_names;
  std::vector<double> position_lower;  // [rad]; −inf when unlimited
  std::vector<double> position_upper;  // [rad]; +inf when unlimited
  std::vector<double> velocity_limit;  // [rad/s]; +inf when none
  std::vector<double> effort_limit;    // [N·m]; +inf when none
  // The joint controller's position PD per joint, or empty; an entry ≤ 0 takes
  // its default (JointController). A simulation's come from its robot config.
  std::vector<double> position_kp;  // [N·m/rad]
  std::vector<double> position_kd;  // [N·m·s/rad]
  // [n] whether each joint has a joint-torque sensor; empty from on_configure():
  // every joint has one (configure() fills it in). read() leaves NaN (not a
  // reading) in SensorReadings::torque for a joint without one.
  std::vector<bool> torque_sensor;
  std::vector<std::string> imu_names;   // order of SensorReadings::imus
  std::vector<std::string> imu_frames;  // frame (link) each IMU sits in
  std::vector<std::string> ft_names;    // order of SensorReadings::force_torque
  std::vector<std::string> ft_frames;   // sensor frame of each F/T sensor

  int n_joints() const { return static_cast<int>(joint_names.size()); }
  // Whether any joint has a joint-torque sensor (else a sample carries no joint torque).
  bool any_torque_sensor() const;
  // Index of a joint; throws std::invalid_argument naming it.
  int joint_index(const std::string& name) const;
};

// Everything read() delivers. Sized once (resize()); read() overwrites values only.
struct SensorReadings {
  Eigen::VectorXd position;      // [n] encoder positions [rad] (quantised, possibly noisy)
  Eigen::VectorXd velocity;      // [n] joint velocities [rad/s]
  Eigen::VectorXd torque;        // [n] joint torques [N·m] (torque sensors / motor current);
                                 // NaN for a joint without a torque sensor
  Eigen::VectorXd pwm;           // [n] motor PWM duty cycle applied, in [−1, 1]
  Time joint_stamp{0};           // source stamp of the joint quantities
  std::vector<ImuReading> imus;  // [n_imus]
  std::vector<ForceTorqueReading> force_torque;  // [n_ft]

  void resize(const BackendDescription& description);
};

// What the hardware accepts per joint: the output of the joint-level control
// (wbi::actuation::JointController) or of a torque controller.
enum class OutputMode : std::uint8_t {
  kIdle,    // unpowered: no motor torque (the joint is passive)
  kTorque,  // value = desired joint torque [N·m] (saturated at the effort limit)
  kPwm,     // value = motor PWM duty cycle in [−1, 1]
};

struct JointCommands {
  std::vector<OutputMode> mode;  // [n]
  Eigen::VectorXd value;         // [n] meaning given by mode
  Time stamp{0};                 // when the commands were computed

  void resize(int n_joints);
  void set_idle();  // every joint IDLE, values 0
};

class RobotBackend {
 public:
  RobotBackend() = default;
  virtual ~RobotBackend() = default;
  RobotBackend(const RobotBackend&) = delete;
  RobotBackend& operator=(const RobotBackend&) = delete;
  RobotBackend(RobotBackend&&) = delete;
  RobotBackend& operator=(RobotBackend&&) = delete;

  // ---- lifecycle (non-virtual: state checks around the on_* hooks) ----
  void configure();   // on_configure() returns the description; buffers are sized from it
  void activate();    // on_activate()
  void deactivate();  // on_deactivate(); commands back to IDLE
  void cleanup();     // on_cleanup(); INACTIVE → UNCONFIGURED (configure() may follow)
  void shutdown();    // on_deactivate() if ACTIVE, then on_shutdown(); → FINALIZED
  LifecycleState state() const { return state_; }

  // ---- cyclic (INACTIVE or ACTIVE; never allocate) ----
  // Reads every sensor into readings(); a joint without a torque sensor
  // (description().torque_sensor) reads NaN as its torque, whatever on_read wrote.
  void read(Time time, Duration period);
  // ACTIVE: applies commands() (sizes checked). INACTIVE: applies IDLE to every joint.
  void write(Time time, Duration period);

  const BackendDescription& description() const { return description_; }
  const SensorReadings& readings() const { return readings_; }
  JointCommands& commands() { return commands_; }
  const JointCommands& commands() const { return commands_; }

 protected:
  // Implementations override these. on_configure must fully describe the
  // hardware; on_read fills `out` (already sized); on_write applies `in`.
  virtual BackendDescription on_configure() = 0;
  virtual void on_activate() {}
  virtual void on_deactivate() {}
  virtual void on_cleanup() {}
  virtual void on_shutdown() {}
  virtual void on_read(Time time, Duration period, SensorReadings& out) = 0;
  virtual void on_write(Time time, Duration period, const JointCommands& in) = 0;

 private:
  LifecycleState state_ = LifecycleState::unconfigured;
  BackendDescription description_;
  SensorReadings readings_;
  JointCommands commands_;
  JointCommands idle_;  // what write() applies when INACTIVE
};

}  // namespace wbi::actuation
