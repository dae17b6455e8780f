#include "wbi/estimation/kalman_derivative.hpp"

namespace wbi::estimation {

KalmanEstimator::KalmanEstimator(Eigen::Index joints, const KalmanParameters& params,
                                 const StreamParameters& stream)
    : DerivativeEstimator(joints, stream),
      chain_("kalman", params.model_order, params.resolution_counts, params.process_noise,
             1.0 / stream.sample_rate_hz),
      x_(IntegratorChain::States::Zero(IntegratorChain::kStates, joints)) {}

void KalmanEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  // At rest at q with the steady-state uncertainty: no start-up transient.
  x_.setZero();
  x_.row(0) = q.transpose();
  chain_.restart();
}

void KalmanEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                           Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  const double h = dt_s / chain_.period_s();
  const IntegratorChain::Matrix F = chain_.transition(h);
  const IntegratorChain::Vector K = chain_.step(h);
  const double to_velocity = 1.0 / chain_.period_s();
  const double to_acceleration = to_velocity * to_velocity;
  for (Eigen::Index j = 0; j < joints(); ++j) {
    // Predict x⁻ = F x, correct x = x⁻ + K (q - x⁻_0).
    IntegratorChain::Vector x = F * x_.col(j);
    x += K * (q(j) - x(0));
    x_.col(j) = x;
    dq(j) = x(1) * to_velocity;
    ddq(j) = x(2) * to_acceleration;
  }
}

}  // namespace wbi::estimation
