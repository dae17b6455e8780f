// The balancing demo's CoM reference: while settling (t < t_s) the origin x₀
// follows the measured CoM (set_origin each tick: a late or corrected first
// base estimate does not become a CoM error), then
//   x_d(t) = x₀ + a sin(2π f (t − t_s)) · direction
// with its analytic velocity and acceleration.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace wbi::controllers {

struct ComSinusoid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitY();  // unit
  double amplitude = 0.05;                               // [m]
  double frequency_hz = 0.2;
  double settle_s = 0.5;

  bool settling(double t) const { return t < settle_s; }

  // Position, velocity, acceleration at time t [s] since the start.
  void at(double t, Eigen::Vector3d& position, Eigen::Vector3d& velocity,
          Eigen::Vector3d& acceleration) const {
    const double w = 2.0 * M_PI * frequency_hz;
    const double s = t > settle_s ? t - settle_s : 0.0;
    const double moving = t > settle_s ? 1.0 : 0.0;
    position = origin + amplitude * std::sin(w * s) * direction;
    velocity = moving * amplitude * w * std::cos(w * s) * direction;
    acceleration = -amplitude * w * w * std::sin(w * s) * direction;
  }
};

}  // namespace wbi::controllers
