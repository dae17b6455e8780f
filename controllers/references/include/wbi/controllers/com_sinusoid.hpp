// The balancing demo's CoM reference. While settling (t < t_s) it holds the
// measured CoM (a late or corrected first base estimate does not become a CoM
// error); then
//   x_d(t) = x₀ + a sin(2π f (t − t_s) + φ) · d
// with its analytic velocity and acceleration. The sinusoid is centred on the
// feet: x₀'s horizontal part along d is the middle of the two soles and φ puts
// x_d(t_s) on the CoM of that moment. A controller that starts on a robot
// already leaning (it was restarted mid-sinusoid) so keeps the swing between
// the feet instead of adding it to the lean (a ±5 cm swing around a CoM 9 cm
// out put it 14 cm out, past the sole, and the humanoid fell). A first start
// on a robot standing straight has φ ≈ 0.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace wbi::controllers {

struct ComSinusoid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitY();  // unit
  double amplitude = 0.05;                               // [m]
  double frequency_hz = 0.2;
  double settle_s = 0.5;
  double phase = 0.0;  // φ [rad]

  bool settling(double t) const { return t < settle_s; }

  // Once per tick, before at(). `com()` and `feet_center()` give the measured
  // CoM and middle of the soles (of the same state); they are called only on
  // the ticks that need them. Holds the CoM while settling; on the first tick
  // after it, centres the sinusoid on the feet and starts it at the CoM.
  template <class Com, class FeetCenter>
  void follow(double t, Com&& com, FeetCenter&& feet_center) {
    if (settling(t)) {
      origin = com();
      phase = 0.0;
      anchored_ = false;
      return;
    }
    if (anchored_) {
      return;
    }
    anchored_ = true;
    const Eigen::Vector3d now = com();
    Eigen::Vector3d lean = now - feet_center();
    lean.z() = 0.0;  // the CoM's height is not a lean
    // Along d; beyond the swing (a start far off the centre) the sinusoid
    // keeps a's range but about the CoM's side, so that x_d starts at the CoM.
    const double offset = std::clamp(lean.dot(direction), -amplitude, amplitude);
    phase = amplitude > 0.0 ? std::asin(offset / amplitude) : 0.0;
    origin = now - offset * direction;
  }

  // Position, velocity, acceleration at time t [s] since the start.
  void at(double t, Eigen::Vector3d& position, Eigen::Vector3d& velocity,
          Eigen::Vector3d& acceleration) const {
    const double w = 2.0 * M_PI * frequency_hz;
    const double angle = (t > settle_s ? w * (t - settle_s) : 0.0) + phase;
    const double moving = t > settle_s ? 1.0 : 0.0;
    position = origin + amplitude * std::sin(angle) * direction;
    velocity = moving * amplitude * w * std::cos(angle) * direction;
    acceleration = moving * -amplitude * w * w * std::sin(angle) * direction;
  }

 private:
  bool anchored_ = false;
};

}  // namespace wbi::controllers
