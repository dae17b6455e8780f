// JointController — joint-level actuator control, run at the backend rate
// between read() and write(). What a motor-control board does on a real robot:
// per-joint control modes, low-level PID loops, limits, a command watchdog.
//
//   IDLE             no output (joint unpowered).
//   POSITION         the target is reached by a minimum-jerk trajectory at the
//                    reference speed, tracked by the position PID (the original
//                    WBI's semantics; for point-to-point moves). A value equal to
//                    the current target (a controller sending the same target every
//                    cycle) leaves the trajectory in progress untouched. A new target
//                    re-plans from the current reference: a quintic from its
//                    (q_r, q̇_r, q̈_r) to (target, 0, 0) in
//                    T = max(min_trajectory_time, 1.875 |target − q_r| / speed) (at
//                    most 10⁶ s: a denormal speed plans no overflow), so
//                    position, velocity and acceleration stay continuous and a target
//                    that moves a little every cycle is followed smoothly: a ramp at
//                    speed v (< 0.89 × reference speed) is tracked at v with a lag of
//                    0.6 v min_trajectory_time (receding-horizon quintic in steady
//                    state: 60 Δ/T³ = 36 v/T²); a faster one is followed at about 0.89 ×
//                    the reference speed. A mode switch into POSITION, or the first
//                    command after a watchdog trip, starts from the measured position
//                    at rest. Streaming controllers (a new position every cycle, to be
//                    tracked as it comes) use POSITION_DIRECT.
//   POSITION_DIRECT  the target is tracked directly by the position PID (streaming);
//                    the reference moves towards the target at most at the
//                    velocity limit per tick.
//   VELOCITY         the velocity reference is integrated into a position
//                    reference (q_r += q̇_r dt) tracked by the position PID with
//                    q̇_r as feed-forward (no drift) (streaming).
//   TORQUE           the value is the joint torque (streaming).
//   PWM              the value is the motor duty cycle in [−1, 1] (streaming); the
//                    backend's motor turns it into torque.
// PID: τ = kp (q_r − q) + kd (q̇_r − q̇) + ki ∫(q_r − q) dt, |ki ∫| ≤ max_integral
// (a NaN from ∞ − ∞ with huge gains counts as 0 before the effort clamp).
// Limits: position references clamped to [lower, upper]; velocity references to
// ±velocity_limit; torques to ±effort_limit. In TORQUE mode a guard adds
// kp (limit − q) beyond a position limit and −kd (q̇ ∓ v_max) beyond the velocity limit.
//
// Commands (submit): a batch names joints (or all), optionally their new modes
// and their values. The whole batch is checked first (unknown or repeated
// joint, wrong size, non-finite value, value for an IDLE joint): on error
// nothing is applied and the error is returned and kept in status(). Accepted
// batches are staged (the result counts the values that lie outside the
// joint's limits and will be clamped); update() applies everything staged at
// the start of the next tick, so mode switches of many joints take effect in
// the same tick.
// submit() may be called from another thread than update() (a mutex guards
// the staging area); read status() on the update() thread. update() never
// allocates; submit() does not allocate when it accepts a batch.
//
// Watchdog: a joint in a streaming mode whose last command is older than
// watchdog_timeout trips: it holds the measured position at the trip (kHold)
// or is damped to rest with τ = −damping_gain q̇ (kDamp); status() reports
// the trip. The next command that addresses the joint clears the trip.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include <wbi/vocabulary/control_mode.hpp>

#include "wbi/actuation/robot_backend.hpp"

namespace wbi::actuation {

// Modes: wbi::ControlMode (wbi/vocabulary/control_mode.hpp), to_string, is_streaming.

struct PidGains {
  double kp = 0.0;            // [N·m/rad]
  double kd = 0.0;            // [N·m·s/rad]
  double ki = 0.0;            // [N·m/(rad·s)]
  double max_integral = 0.0;  // bound on |ki ∫e| [N·m]; ≤ 0: the effort limit
};

enum class WatchdogAction : std::uint8_t { kHold, kDamp };

struct JointControllerConfig {
  // Gains per joint (size n) or empty: the description's position_kp and
  // position_kd where given (> 0), else kp = 10·effort_limit [N·m/rad] (100 when
  // the effort is unlimited) and kd = kp/200 [s]; ki = 0.
  // Tune them: explicit PD at rate 1/h is stable for kd ≲ m_eff/h.
  std::vector<PidGains> gains;
  double reference_speed = 0.5;       // POSITION default peak speed [rad/s]
  double min_trajectory_time = 0.02;  // [s]
  double watchdog_timeout = 0.1;      // [s]; ≤ 0 disables the watchdog
  WatchdogAction watchdog_action = WatchdogAction::kHold;
  double damping_gain = 0.0;  // kDamp [N·m·s/rad]; ≤ 0: the joint's kd
};

// One command message: joints by name, or by index in the description's order
// (what the wire carries: no name lookup per command); both empty = every joint
// in order.
struct JointCommandBatch {
  std::vector<std::string> joints;
  std::vector<int> joint_indices;        // alternative to joints (give one or the other)
  std::vector<ControlMode> modes;        // empty: keep modes; else one per joint
  std::vector<double> values;            // empty: mode switch only; else one per joint
  std::vector<double> reference_speeds;  // POSITION only; empty or one per joint [rad/s]
};

struct CommandResult {
  bool ok = true;
  std::string error;  // empty when ok
  int clamped = 0;    // accepted values outside the joint's limits (they will be clamped)
};

struct JointControlStatus {
  std::vector<ControlMode> mode;               // [n] active mode
  std::vector<std::uint8_t> watchdog_tripped;  // [n] 1 while tripped
  Eigen::VectorXd position_reference;          // [n] q_r of the last tick
  Eigen::VectorXd velocity_reference;          // [n] q̇_r of the last tick
  Eigen::VectorXd output;                      // [n] torque or PWM sent
  std::uint64_t watchdog_trips = 0;            // total since construction
  std::uint64_t accepted_batches = 0;
  std::uint64_t rejected_batches = 0;
  std::string last_error;  // of the last rejected batch
};

class JointController {
 public:
  JointController(const BackendDescription& description, JointControllerConfig config = {});

  // Checks and stages a batch (see above). `now`: arrival time, for the watchdog.
  CommandResult submit(const JointCommandBatch& batch, Time now);
  void set_gains(const std::string& joint, const PidGains& gains);  // throws on unknown joint
  const PidGains& gains(int joint) const { return gains_[static_cast<std::size_t>(joint)]; }

  // One tick: applies staged commands, runs the watchdog, the trajectories and
  // the PID loops on `in`, writes `out`. Never allocates.
  void update(Time now, Duration period, const SensorReadings& in, JointCommands& out);

  // State of every joint after the last update(), counters, last error.
  const JointControlStatus& status() const { return status_; }
  int n_joints() const { return n_; }

 private:
  struct Staged {
    bool has_mode = false;
    ControlMode mode = ControlMode::idle;
    bool has_value = false;
    double value = 0.0;
    double speed = 0.0;  // ≤ 0: default
    bool touched = false;
    Time time{0};
  };
  struct Joint {
    ControlMode mode = ControlMode::idle;
    double target = 0.0;  // command value (position, velocity, torque, PWM)
    double speed = 0.0;   // POSITION reference speed
    double q_r = 0.0, dq_r = 0.0;
    double ddq_r = 0.0;  // POSITION: the trajectory's acceleration (re-planning keeps it)
    double integral = 0.0;
    Time last_command{0};
    bool tripped = false;
    bool start_trajectory = false;
    bool init_reference = false;
    // minimum-jerk trajectory: q(t) = Σ c_k (t − t0)^k, k = 0…5, t ≤ duration
    double c[6] = {0, 0, 0, 0, 0, 0};
    double t0 = 0.0, duration = 0.0;
  };

  int find(const std::string& name) const;
  bool outside_limits(ControlMode mode, double value, std::size_t joint) const;
  void start_trajectory(Joint& j, int i, double t);
  double pid(Joint& j, int i, double q, double dq, double dt);

  int n_ = 0;
  BackendDescription description_;
  JointControllerConfig config_;
  std::vector<PidGains> gains_;
  std::vector<Joint> joints_;
  std::vector<Staged> staged_;
  std::vector<int> scratch_index_;  // [n] batch → joint
  std::mutex mutex_;
  JointControlStatus status_;
};

}  // namespace wbi::actuation
