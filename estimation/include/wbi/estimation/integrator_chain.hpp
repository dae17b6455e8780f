// The model of the Kalman estimator: each joint is a chain of integrators
// (q, dq, ..., d^m q), m the model order (2: constant acceleration, 3:
// constant jerk, 4: constant snap), whose derivative m+1 is continuous white
// noise of density σ_w², measured through an encoder of step Δ = 2π / counts
// (quantisation variance r = Δ²/12):
//
//   x_k = F(Δt) x_(k-1) + w,  w ~ N(0, Q(Δt)),   z_k = H x_k + v,  H = (1 0 … 0),  v ~ N(0, r)
//
// F and Q are the exact discretisation of the integrator chain (Bar-Shalom,
// Li and Kirubarajan, "Estimation with Applications to Tracking and
// Navigation", Wiley 2001, §6.2–6.3). All joints share stamps and noise model,
// so they share this covariance: the Riccati step runs once per sample.
//
// Units are scaled: derivative i is stored times T^i (T the nominal period)
// so that the covariance entries stay within a few decades of each other.
#pragma once

#include <Eigen/Core>

namespace wbi::estimation {

class IntegratorChain {
 public:
  // q and up to four derivatives; an order-m model leaves states m+1.. at zero.
  static constexpr int kStates = 5;
  using Matrix = Eigen::Matrix<double, kStates, kStates>;
  using Vector = Eigen::Matrix<double, kStates, 1>;
  using States = Eigen::Matrix<double, kStates, Eigen::Dynamic>;  // one column per joint

  // order 2, 3 or 4; counts >= 2; sigma_w > 0 (σ_w, rad/s^(order+1)/√Hz);
  // period_s > 0. Throws std::invalid_argument naming `method` otherwise.
  IntegratorChain(const char* method, int order, double counts, double sigma_w, double period_s);

  // F for an interval of h nominal periods (scaled units).
  Matrix transition(double h) const;
  // Advances the covariance by h periods and corrects it with one measurement.
  // Returns the Kalman gain (scaled units).
  Vector step(double h) { return riccati_step(P_, h); }
  // Back to the steady-state covariance of the nominal rate.
  void restart() { P_ = P_steady_; }

  double period_s() const { return period_s_; }
  // r = Δ²/12 of an encoder with `counts` per revolution, rad².
  static double quantisation_variance(double counts);
  // Steady-state gain at the nominal rate in SI units (for documentation and tests).
  Vector steady_state_gain() const;

 private:
  Matrix process_noise(double h) const;
  Vector riccati_step(Matrix& P, double h) const;

  int order_;
  double period_s_;
  double measurement_variance_;  // r = Δ²/12, rad²
  double noise_density_;         // σ_w² T^(2 order + 1), scaled units
  Matrix P_steady_;              // posterior covariance in steady state
  Matrix P_;                     // current posterior covariance
};

}  // namespace wbi::estimation
