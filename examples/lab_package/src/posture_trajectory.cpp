#include "posture_trajectory.hpp"

#include <cmath>

namespace lab {

double PostureTrajectory::end_s() const {
  return start_s + move_s + static_cast<double>(sway_periods) / sway_hz;
}

void PostureTrajectory::at(double t, Eigen::VectorXd& x, Eigen::VectorXd& v,
                           Eigen::VectorXd& a) const {
  const double move_end_s = start_s + move_s;
  if (t < start_s || t >= end_s()) {
    x = t < start_s ? from : target;
    v.setZero();
    a.setZero();
    return;
  }
  if (t < move_end_s) {
    // Minimum jerk: s, ds/dt, d²s/dt² of τ = (t − start_s) / move_s.
    const double tau = (t - start_s) / move_s;
    const double s = tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
    const double ds = 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau) / move_s;
    const double dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau) / (move_s * move_s);
    x = from + s * (target - from);
    v = ds * (target - from);
    a = dds * (target - from);
    return;
  }
  // The sway: (1 − cos φ) / 2 and its derivatives, φ = ω (t − t_move).
  const double omega = 2.0 * M_PI * sway_hz;
  const double phase = omega * (t - move_end_s);
  x = target + 0.5 * (1.0 - std::cos(phase)) * sway;
  v = 0.5 * omega * std::sin(phase) * sway;
  a = 0.5 * omega * omega * std::cos(phase) * sway;
}

}  // namespace lab
