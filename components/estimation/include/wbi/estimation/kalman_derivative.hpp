// Kalman filter on a chain-of-integrators model of each joint, the method
// this library recommends. The state is (q, dq, ddq, dddq); the highest
// modelled derivative (jerk for model order 3, acceleration for order 2)
// is driven by continuous white noise of density σ_w² and the measurement
// is q quantised by the encoder, variance r = Δ²/12 with Δ = 2π / counts.
//
//   x_k = F(Δt) x_(k-1) + w,  w ~ N(0, Q(Δt)),   z_k = q_k = H x_k + v,  v ~ N(0, r)
//
// (Bar-Shalom, Li and Kirubarajan, "Estimation with Applications to Tracking
// and Navigation", 2001, §6.2–6.3, for F and Q of the white-noise-driven
// integrator chain.) All joints share the stamps and the noise model, so they
// share one 4×4 covariance: its Riccati update runs once per sample, then each
// joint costs a 4×4 prediction and a rank-one correction. The covariance
// starts at its steady state for the nominal rate and follows the actual
// intervals, so dropped samples and jitter keep the filter optimal.
#pragma once

#include "wbi/estimation/derivative_estimator.hpp"

namespace wbi::estimation {

struct KalmanParameters {
  int model_order = 3;             // 3: constant jerk (white snap); 2: constant acceleration (white jerk)
  double resolution_counts = 16384.0;  // encoder counts per revolution (2^14)
  double process_noise = 3.0e4;    // σ_w: density of the white noise driving the highest derivative,
                                   // rad/s^(order+1)/√Hz
};

class KalmanEstimator final : public DerivativeEstimator {
 public:
  using Matrix4 = Eigen::Matrix4d;
  using Vector4 = Eigen::Vector4d;

  KalmanEstimator(Eigen::Index joints, const KalmanParameters& params,
                  const StreamParameters& stream = {});
  const char* method() const override { return "kalman"; }

  // Steady-state gain at the nominal rate for (q, dq, ddq, dddq) in SI units:
  // the filter's frequency response, for the documentation and the tests.
  Vector4 steady_state_gain() const;

 private:
  void start(const Eigen::Ref<const Eigen::VectorXd>& q) override;
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
            Eigen::VectorXd& ddq) override;

  // The model in scaled units: derivative i is stored times T^i (T the nominal
  // period) so the covariance entries stay within a few decades of each other.
  Matrix4 transition(double h) const;      // F for an interval of h periods
  Matrix4 process_noise(double h) const;   // Q for an interval of h periods
  // One covariance step: predicts over h periods, corrects; returns the gain.
  Vector4 riccati_step(Matrix4& P, double h) const;

  KalmanParameters params_;
  double period_s_;                // nominal T
  double measurement_variance_;    // r = Δ²/12, rad²
  double noise_density_scaled_;    // σ_w² T^(2 order + 1)
  Matrix4 P_steady_;               // posterior covariance in steady state (scaled)
  Matrix4 P_;                      // current posterior covariance (scaled)
  Eigen::Matrix<double, 4, Eigen::Dynamic> x_;  // (4 × joints) scaled state per joint
};

}  // namespace wbi::estimation
