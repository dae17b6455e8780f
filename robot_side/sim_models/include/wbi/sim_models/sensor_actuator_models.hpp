// The sensor, actuator and joint models every simulation engine shares (the own
// plant, MuJoCo): Gaussian noise, encoder quantisation, the DC motor behind a
// PWM command, joint dissipation, so that a reading, a PWM duty or a friction
// torque means the same in both. Nothing here allocates.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "wbi/actuation/robot_backend.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::sim_models {

// Gaussian numbers from mt19937_64 by Box–Muller: the same sequence on every
// platform (std::normal_distribution is implementation-defined).
class Gaussian {
 public:
  explicit Gaussian(std::uint64_t seed) : rng_(seed) {}
  double operator()(double sigma) {
    if (sigma <= 0.0) {
      return 0.0;
    }
    if (has_spare_) {
      has_spare_ = false;
      return sigma * spare_;
    }
    constexpr double kScale = 1.0 / 18446744073709551616.0;  // 2^-64
    double u1 = 0.0;
    do {
      u1 = static_cast<double>(rng_()) * kScale;
    } while (u1 <= 0.0);
    const double u2 = static_cast<double>(rng_()) * kScale;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return sigma * r * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// x rounded to the nearest multiple of step (step ≤ 0: x).
inline double quantise(double x, double step) {
  return step > 0.0 ? step * std::round(x / step) : x;
}

// Encoder resolution [rad] of robot_config::EncoderConfig (0: none).
inline double encoder_step(const robot_config::EncoderConfig& encoders) {
  return encoders.counts_per_revolution > 0.0 ? 2.0 * M_PI / encoders.counts_per_revolution : 0.0;
}

// The DC motor of one joint (robot_config::MotorConfig), referred to the joint:
//   τ = k_t (V·pwm − k_e q̇) / R.
struct DcMotor {
  double k_t = 0.0;  // [N·m/A]
  double k_e = 0.0;  // [V·s/rad]
  double voltage = 24.0;
  double resistance = 1.0;

  // From the config; k_t ≤ 0 there: stall torque = the joint's effort limit
  // (100 N·m when unlimited).
  static DcMotor from(const robot_config::MotorConfig& c, double effort_limit) {
    DcMotor m;
    const double stall = std::isfinite(effort_limit) ? effort_limit : 100.0;
    m.k_t = c.torque_constant > 0.0 ? c.torque_constant : stall * c.resistance / c.voltage;
    m.k_e = c.back_emf > 0.0 ? c.back_emf : m.k_t;
    m.voltage = c.voltage;
    m.resistance = c.resistance;
    return m;
  }
  // Torque at duty pwm (clamped to [−1, 1]) and joint velocity dq (not saturated).
  double torque(double pwm, double dq) const {
    return k_t * (voltage * std::clamp(pwm, -1.0, 1.0) - k_e * dq) / resistance;
  }
  // The duty that gives torque tau at velocity dq, clamped to [−1, 1].
  double duty(double tau, double dq) const {
    return std::clamp((tau * resistance / k_t + k_e * dq) / voltage, -1.0, 1.0);
  }
};

// What one joint's actuator applies for a held command at joint velocity dq:
// the torque, saturated at the effort limit (IDLE: none; PWM: the motor's), and
// the PWM duty that goes with it (the command's when it is a duty, else the
// motor's at that torque).
struct ActuatorOutput {
  double torque = 0.0;  // [N·m]
  double pwm = 0.0;     // [−1, 1]
};
inline ActuatorOutput actuator_output(actuation::OutputMode mode, double value, double dq,
                                      const DcMotor& motor, double effort_limit) {
  ActuatorOutput out;
  switch (mode) {
    case actuation::OutputMode::kIdle:
      break;
    case actuation::OutputMode::kTorque:
      out.torque = value;
      break;
    case actuation::OutputMode::kPwm:
      out.torque = motor.torque(value, dq);
      break;
  }
  out.torque = std::clamp(out.torque, -effort_limit, effort_limit);
  out.pwm = mode == actuation::OutputMode::kPwm ? std::clamp(value, -1.0, 1.0)
                                                : motor.duty(out.torque, dq);
  return out;
}

// A joint's own dissipation: viscous damping and Coulomb friction smoothed by
// tanh(q̇ / v_f), bounded so that, applied explicitly over a step h, it never
// reverses q̇ of a joint of effective inertia m_eff = 1/(M⁻¹)_jj.
inline double dissipation_torque(double dq, double damping, double friction,
                                 double friction_velocity, double m_eff, double h) {
  const double torque = -damping * dq - friction * std::tanh(dq / friction_velocity);
  const double bound = 0.5 * m_eff * std::abs(dq) / h;
  return std::clamp(torque, -bound, bound);
}

}  // namespace wbi::sim_models
