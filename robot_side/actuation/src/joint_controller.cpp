// Joint-level actuator control (see joint_controller.hpp for the behaviour).
#include "wbi/actuation/joint_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wbi::actuation {

namespace {
double seconds(Duration d) { return static_cast<double>(d.count()) * 1e-9; }
// The description's position PD where it gives one, else kp from the effort
// limit and kd = kp/200.
PidGains default_gains(const BackendDescription& d, std::size_t joint) {
  auto given = [joint](const std::vector<double>& gains) {
    return joint < gains.size() && gains[joint] > 0.0 ? gains[joint] : 0.0;
  };
  PidGains g;
  const double effort = d.effort_limit[joint];
  g.kp = given(d.position_kp);
  if (g.kp == 0.0) {
    g.kp = std::isfinite(effort) ? 10.0 * effort : 100.0;
  }
  g.kd = given(d.position_kd);
  if (g.kd == 0.0) {
    g.kd = g.kp / 200.0;
  }
  return g;
}

}  // namespace

JointController::JointController(const BackendDescription& description,
                                 JointControllerConfig config)
    : n_(description.n_joints()), description_(description), config_(std::move(config)) {
  const auto n = static_cast<std::size_t>(n_);
  if (!config_.gains.empty() && config_.gains.size() != n) {
    throw std::invalid_argument("joint controller: 'gains' has " +
                                std::to_string(config_.gains.size()) + " entries, expected " +
                                std::to_string(n) + " (one per joint)");
  }
  gains_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!config_.gains.empty()) {
      gains_[i] = config_.gains[i];
    } else {
      gains_[i] = default_gains(description_, i);
    }
  }
  joints_.resize(n);
  staged_.resize(n);
  scratch_index_.resize(n);
  status_.mode.assign(n, ControlMode::idle);
  status_.watchdog_tripped.assign(n, 0);
  status_.position_reference = Eigen::VectorXd::Zero(n_);
  status_.velocity_reference = Eigen::VectorXd::Zero(n_);
  status_.output = Eigen::VectorXd::Zero(n_);
}

int JointController::find(const std::string& name) const {
  for (int i = 0; i < n_; ++i) {
    if (description_.joint_names[static_cast<std::size_t>(i)] == name) {
      return i;
    }
  }
  return -1;
}

void JointController::set_gains(const std::string& joint, const PidGains& gains) {
  const int i = find(joint);
  if (i < 0) {
    throw std::invalid_argument("joint controller: set_gains: unknown joint '" + joint + "'");
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  gains_[static_cast<std::size_t>(i)] = gains;
}

CommandResult JointController::submit(const JointCommandBatch& batch, Time now) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto reject = [&](std::string error) {
    ++status_.rejected_batches;
    status_.last_error = error;
    return CommandResult{false, std::move(error)};
  };
  const bool by_index = !batch.joint_indices.empty();
  if (by_index && !batch.joints.empty()) {
    return reject("command names joints both by name and by index");
  }
  const bool all = !by_index && batch.joints.empty();
  const std::size_t k = all        ? static_cast<std::size_t>(n_)
                        : by_index ? batch.joint_indices.size()
                                   : batch.joints.size();
  if (k > static_cast<std::size_t>(n_)) {
    return reject("command names " + std::to_string(k) + " joints, the robot has " +
                  std::to_string(n_));
  }
  auto size_ok = [&](std::size_t s) { return s == 0 || s == k; };
  if (!size_ok(batch.modes.size())) {
    return reject("command has " + std::to_string(batch.modes.size()) + " modes for " +
                  std::to_string(k) + " joints");
  }
  if (!size_ok(batch.values.size())) {
    return reject("command has " + std::to_string(batch.values.size()) + " values for " +
                  std::to_string(k) + " joints");
  }
  if (!size_ok(batch.reference_speeds.size())) {
    return reject("command has " + std::to_string(batch.reference_speeds.size()) +
                  " reference speeds for " + std::to_string(k) + " joints");
  }
  if (batch.modes.empty() && batch.values.empty()) {
    return reject("command has neither modes nor values");
  }
  // resolve names, reject unknown and repeated joints
  for (std::size_t b = 0; b < k; ++b) {
    const int i = all        ? static_cast<int>(b)
                  : by_index ? batch.joint_indices[b]
                             : find(batch.joints[b]);
    if (by_index && (i < 0 || i >= n_)) {
      return reject("joint index " + std::to_string(i) + " out of range (the robot has " +
                    std::to_string(n_) + " joints)");
    }
    if (i < 0) {
      return reject("unknown joint '" + batch.joints[b] + "'");
    }
    for (std::size_t e = 0; e < b; ++e) {
      if (scratch_index_[e] == i) {
        return reject("joint '" + description_.joint_names[static_cast<std::size_t>(i)] +
                      "' appears twice");
      }
    }
    scratch_index_[b] = i;
  }
  int clamped = 0;
  for (std::size_t b = 0; b < k; ++b) {
    const auto i = static_cast<std::size_t>(scratch_index_[b]);
    const ControlMode mode = !batch.modes.empty()  ? batch.modes[b]
                             : staged_[i].has_mode ? staged_[i].mode
                                                   : joints_[i].mode;
    const std::string& name = description_.joint_names[i];
    if (!batch.values.empty()) {
      if (!std::isfinite(batch.values[b])) {
        return reject("joint '" + name + "': value " + std::to_string(batch.values[b]) +
                      " is not finite");
      }
      // A value for a joint left IDLE is a mistake; a value that comes with an
      // explicit switch to IDLE (the wire carries one per joint) is ignored.
      if (mode == ControlMode::idle && batch.modes.empty()) {
        return reject("joint '" + name + "' is IDLE: it takes no value");
      }
      clamped += outside_limits(mode, batch.values[b], i) ? 1 : 0;
    }
    if (!batch.reference_speeds.empty() && !(batch.reference_speeds[b] > 0.0)) {
      return reject("joint '" + name + "': reference speed " +
                    std::to_string(batch.reference_speeds[b]) + " must be > 0");
    }
  }
  // accepted: stage everything
  for (std::size_t b = 0; b < k; ++b) {
    Staged& s = staged_[static_cast<std::size_t>(scratch_index_[b])];
    if (!batch.modes.empty()) {
      s.has_mode = true;
      s.mode = batch.modes[b];
    }
    if (!batch.values.empty()) {
      s.has_value = true;
      s.value = batch.values[b];
    }
    if (!batch.reference_speeds.empty()) {
      s.speed = batch.reference_speeds[b];
    }
    s.touched = true;
    s.time = now;
  }
  ++status_.accepted_batches;
  return {true, {}, clamped};
}

// What update() will clamp: positions to [lower, upper], velocities to
// ±velocity_limit, torques to ±effort_limit, PWM to [−1, 1].
bool JointController::outside_limits(ControlMode mode, double value, std::size_t joint) const {
  switch (mode) {
    case ControlMode::position:
    case ControlMode::position_direct:
      return value < description_.position_lower[joint] ||
             value > description_.position_upper[joint];
    case ControlMode::velocity:
      return std::abs(value) > description_.velocity_limit[joint];
    case ControlMode::torque:
      return std::abs(value) > description_.effort_limit[joint];
    case ControlMode::pwm:
      return std::abs(value) > 1.0;
    case ControlMode::idle:
      return false;
  }
  return false;
}

// Quintic from (q, q̇, q̈) to (target, 0, 0) in time T: minimum jerk when it
// starts at rest; from a moving reference, position, velocity and acceleration
// stay continuous. T = max(min_trajectory_time, 1.875 |Δ| / v) is the time in
// which a rest-to-rest minimum-jerk move reaches the peak speed v (1.875 Δ/T at T/2).
void JointController::start_trajectory(Joint& j, int i, double t) {
  const auto u = static_cast<std::size_t>(i);
  const double v_max =
      std::min(j.speed > 0.0 ? j.speed : config_.reference_speed, description_.velocity_limit[u]);
  const double q = j.q_r, dq = j.dq_r, a0 = j.ddq_r;
  const double delta = j.target - q;
  // A speed so small that T overflows (a denormal from the wire is > 0) plans
  // an "endless" move instead: the coefficients stay finite.
  constexpr double kLongest = 1e6;  // [s]
  double T = 1.875 * std::abs(delta) / v_max;
  T = T <= kLongest ? std::max(config_.min_trajectory_time, T) : kLongest;
  const double T2 = T * T, T3 = T2 * T;
  j.t0 = t;
  j.duration = T;
  j.c[0] = q;
  j.c[1] = dq;
  j.c[2] = 0.5 * a0;
  j.c[3] = (20.0 * delta - 12.0 * dq * T - 3.0 * a0 * T2) / (2.0 * T3);
  j.c[4] = (-30.0 * delta + 16.0 * dq * T + 3.0 * a0 * T2) / (2.0 * T3 * T);
  j.c[5] = (12.0 * delta - 6.0 * dq * T - a0 * T2) / (2.0 * T3 * T2);
}

double JointController::pid(Joint& j, int i, double q, double dq, double dt) {
  const auto u = static_cast<std::size_t>(i);
  const PidGains& g = gains_[u];
  const double effort = description_.effort_limit[u];
  const double e = j.q_r - q;
  if (g.ki != 0.0) {
    const double bound = (g.max_integral > 0.0 ? g.max_integral : effort) / std::abs(g.ki);
    j.integral = std::clamp(j.integral + e * dt, -bound, bound);
  }
  double tau = g.kp * e + g.kd * (j.dq_r - dq) + g.ki * j.integral;
  if (std::isnan(tau)) {
    tau = 0.0;  // huge gains: +inf from one term and −inf from another
  }
  return std::clamp(tau, -effort, effort);
}

void JointController::update(Time now, Duration period, const SensorReadings& in,
                             JointCommands& out) {
  if (in.position.size() != n_ || in.velocity.size() != n_ || out.value.size() != n_ ||
      out.mode.size() != static_cast<std::size_t>(n_)) {
    throw std::invalid_argument("joint controller: readings or commands are not sized for " +
                                std::to_string(n_) + " joints");
  }
  const double t = seconds(now);
  const double dt = seconds(period);
  {
    // apply the staged commands, all in this tick
    const std::lock_guard<std::mutex> lock(mutex_);
    for (int i = 0; i < n_; ++i) {
      const auto u = static_cast<std::size_t>(i);
      Staged& s = staged_[u];
      if (!s.touched) {
        continue;
      }
      Joint& j = joints_[u];
      const double q = in.position[i];
      if (s.has_mode && (s.mode != j.mode || j.tripped)) {
        j.mode = s.mode;
        j.integral = 0.0;
        j.q_r = q;  // bumpless: references start at the measured state, at rest
        j.dq_r = 0.0;
        j.ddq_r = 0.0;
        j.target =
            j.mode == ControlMode::position || j.mode == ControlMode::position_direct ? q : 0.0;
        j.start_trajectory = j.mode == ControlMode::position;
      }
      if (s.has_value) {
        if (j.mode == ControlMode::position) {
          // the same target again (a controller streaming it) leaves the
          // trajectory in progress alone; a new one re-plans from the reference
          const double target =
              std::clamp(s.value, description_.position_lower[u], description_.position_upper[u]);
          j.start_trajectory = j.start_trajectory || target != j.target;
          j.target = target;
        } else {
          j.target = s.value;
        }
      }
      if (s.speed > 0.0 && s.speed != j.speed) {
        j.speed = s.speed;
        j.start_trajectory = j.start_trajectory || j.mode == ControlMode::position;
      }
      j.tripped = false;
      j.last_command = s.time;
      s = Staged{};
    }
  }
  for (int i = 0; i < n_; ++i) {
    const auto u = static_cast<std::size_t>(i);
    Joint& j = joints_[u];
    const double q = in.position[i];
    const double dq = in.velocity[i];
    const double lower = description_.position_lower[u];
    const double upper = description_.position_upper[u];
    const double v_max = description_.velocity_limit[u];
    const double effort = description_.effort_limit[u];
    // watchdog
    if (!j.tripped && is_streaming(j.mode) && config_.watchdog_timeout > 0.0 &&
        seconds(now - j.last_command) > config_.watchdog_timeout) {
      j.tripped = true;
      ++status_.watchdog_trips;
      j.q_r = std::clamp(q, lower, upper);
      j.dq_r = 0.0;
      j.ddq_r = 0.0;
      j.integral = 0.0;
    }
    OutputMode out_mode = OutputMode::kTorque;
    double value = 0.0;
    if (j.tripped) {
      if (config_.watchdog_action == WatchdogAction::kHold) {
        value = pid(j, i, q, dq, dt);
      } else {
        const double k = config_.damping_gain > 0.0 ? config_.damping_gain : gains_[u].kd;
        value = std::clamp(-k * dq, -effort, effort);
        j.q_r = q;
      }
    } else {
      switch (j.mode) {
        case ControlMode::idle:
          out_mode = OutputMode::kIdle;
          j.q_r = q;
          j.dq_r = 0.0;
          break;
        case ControlMode::position: {
          j.target = std::clamp(j.target, lower, upper);
          if (j.start_trajectory) {
            // from the reference's (q_r, q̇_r, q̈_r), which are those of the last tick
            start_trajectory(j, i, t - dt);
            j.start_trajectory = false;
          }
          const double s = std::clamp(t - j.t0, 0.0, j.duration);
          const double* c = j.c;
          if (t - j.t0 >= j.duration) {
            j.q_r = j.target;
            j.dq_r = 0.0;
            j.ddq_r = 0.0;
          } else {
            j.q_r = c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))));
            j.dq_r = c[1] + s * (2 * c[2] + s * (3 * c[3] + s * (4 * c[4] + s * 5 * c[5])));
            j.ddq_r = 2 * c[2] + s * (6 * c[3] + s * (12 * c[4] + s * 20 * c[5]));
            // a re-planned move from speed may overshoot a target at a limit
            j.q_r = std::clamp(j.q_r, lower, upper);
          }
          value = pid(j, i, q, dq, dt);
          break;
        }
        case ControlMode::position_direct: {
          const double target = std::clamp(j.target, lower, upper);
          const double step = std::isfinite(v_max) ? v_max * dt : std::abs(target - j.q_r);
          const double next = j.q_r + std::clamp(target - j.q_r, -step, step);
          j.dq_r = 0.0;
          j.q_r = next;
          value = pid(j, i, q, dq, dt);
          break;
        }
        case ControlMode::velocity: {
          j.dq_r = std::clamp(j.target, -v_max, v_max);
          j.q_r = std::clamp(j.q_r + j.dq_r * dt, lower, upper);
          if (j.q_r == lower || j.q_r == upper) {
            j.dq_r = 0.0;
          }
          value = pid(j, i, q, dq, dt);
          break;
        }
        case ControlMode::torque: {
          double tau = j.target;
          const PidGains& g = gains_[u];
          if (q > upper) {
            tau = std::min(tau, 0.0) + g.kp * (upper - q);
          } else if (q < lower) {
            tau = std::max(tau, 0.0) + g.kp * (lower - q);
          }
          if (dq > v_max) {
            tau -= g.kd * (dq - v_max);
          } else if (dq < -v_max) {
            tau -= g.kd * (dq + v_max);
          }
          value = std::clamp(tau, -effort, effort);
          j.q_r = q;
          j.dq_r = dq;
          break;
        }
        case ControlMode::pwm:
          out_mode = OutputMode::kPwm;
          value = std::clamp(j.target, -1.0, 1.0);
          j.q_r = q;
          j.dq_r = dq;
          break;
      }
    }
    out.mode[u] = out_mode;
    out.value[i] = value;
    status_.mode[u] = j.mode;
    status_.watchdog_tripped[u] = j.tripped ? 1 : 0;
    status_.position_reference[i] = j.q_r;
    status_.velocity_reference[i] = j.dq_r;
    status_.output[i] = value;
  }
  out.stamp = now;
}

}  // namespace wbi::actuation
