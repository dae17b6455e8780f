#include "wbi/estimation/kalman_derivative.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wbi::estimation {
namespace {

double factorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) {
    f *= i;
  }
  return f;
}

}  // namespace

KalmanEstimator::KalmanEstimator(Eigen::Index joints, const KalmanParameters& params,
                                 const StreamParameters& stream)
    : DerivativeEstimator(joints, stream), params_(params) {
  if (params.model_order != 2 && params.model_order != 3) {
    throw std::invalid_argument("kalman: model-order must be 2 or 3, got " +
                                std::to_string(params.model_order));
  }
  if (!(params.resolution_counts >= 2.0) || !std::isfinite(params.resolution_counts)) {
    throw std::invalid_argument("kalman: resolution must be >= 2 counts per revolution, got " +
                                std::to_string(params.resolution_counts));
  }
  if (!(params.process_noise > 0.0) || !std::isfinite(params.process_noise)) {
    throw std::invalid_argument("kalman: process-noise must be > 0, got " +
                                std::to_string(params.process_noise));
  }
  period_s_ = 1.0 / stream.sample_rate_hz;
  const double step_rad = 2.0 * std::numbers::pi / params.resolution_counts;
  measurement_variance_ = step_rad * step_rad / 12.0;
  noise_density_scaled_ = params.process_noise * params.process_noise *
                          std::pow(period_s_, 2 * params.model_order + 1);

  // Steady state of the Riccati recursion at the nominal period; it converges
  // geometrically, a few hundred steps at most for sensible parameters.
  P_steady_ = process_noise(1.0);
  for (int i = 0; i < 100000; ++i) {
    const Matrix4 previous = P_steady_;
    riccati_step(P_steady_, 1.0);
    if ((P_steady_ - previous).norm() <= 1e-13 * P_steady_.norm()) {
      break;
    }
  }
  P_ = P_steady_;
  x_ = Eigen::Matrix<double, 4, Eigen::Dynamic>::Zero(4, joints);
}

KalmanEstimator::Matrix4 KalmanEstimator::transition(double h) const {
  // F_ij = h^(j-i) / (j-i)! for i <= j <= order: exact for the integrator chain.
  Matrix4 F = Matrix4::Zero();
  for (int i = 0; i <= params_.model_order; ++i) {
    for (int j = i; j <= params_.model_order; ++j) {
      F(i, j) = std::pow(h, j - i) / factorial(j - i);
    }
  }
  return F;
}

KalmanEstimator::Matrix4 KalmanEstimator::process_noise(double h) const {
  // Q = s ∫_0^h φ(τ) φ(τ)^T dτ with φ_i(τ) = τ^(m-i)/(m-i)!, m the order:
  // Q_ij = s h^(2m-i-j+1) / ((m-i)! (m-j)! (2m-i-j+1)).
  const int m = params_.model_order;
  Matrix4 Q = Matrix4::Zero();
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j <= m; ++j) {
      const int p = 2 * m - i - j + 1;
      Q(i, j) = noise_density_scaled_ * std::pow(h, p) / (factorial(m - i) * factorial(m - j) * p);
    }
  }
  return Q;
}

KalmanEstimator::Vector4 KalmanEstimator::riccati_step(Matrix4& P, double h) const {
  const Matrix4 F = transition(h);
  P = F * P * F.transpose() + process_noise(h);
  // H = (1 0 0 0): the innovation variance is P_00 + r, the gain P's first column over it.
  const Vector4 K = P.col(0) / (P(0, 0) + measurement_variance_);
  P -= K * P.row(0);
  P = 0.5 * (P + P.transpose()).eval();  // keep it symmetric against rounding
  return K;
}

KalmanEstimator::Vector4 KalmanEstimator::steady_state_gain() const {
  Matrix4 P = P_steady_;
  Vector4 K = riccati_step(P, 1.0);
  for (int i = 0; i < 4; ++i) {
    K(i) /= std::pow(period_s_, i);  // scaled units back to SI
  }
  return K;
}

void KalmanEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  // At rest at q, with the steady-state uncertainty: no start-up transient.
  x_.setZero();
  x_.row(0) = q.transpose();
  P_ = P_steady_;
}

void KalmanEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                           Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  const double h = dt_s / period_s_;
  const Matrix4 F = transition(h);
  const Vector4 K = riccati_step(P_, h);
  const double to_velocity = 1.0 / period_s_;
  const double to_acceleration = to_velocity * to_velocity;
  for (Eigen::Index j = 0; j < joints(); ++j) {
    // Predict x⁻ = F x, correct x = x⁻ + K (q - x⁻_0).
    Vector4 x = F * x_.col(j);
    x += K * (q(j) - x(0));
    x_.col(j) = x;
    dq(j) = x(1) * to_velocity;
    ddq(j) = x(2) * to_acceleration;
  }
}

}  // namespace wbi::estimation
