#include "wbi/estimation/integrator_chain.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wbi::estimation {
namespace {

constexpr double kFactorial[10] = {1, 1, 2, 6, 24, 120, 720, 5040, 40320, 362880};

}  // namespace

IntegratorChain::IntegratorChain(const char* method, int order, double counts, double sigma_w,
                                 double period_s)
    : order_(order), period_s_(period_s) {
  const std::string name(method);
  if (order < 2 || order > kStates - 1) {
    throw std::invalid_argument(name + ": model-order must be 2, 3 or 4, got " +
                                std::to_string(order));
  }
  if (!(counts >= 2.0) || !std::isfinite(counts)) {
    throw std::invalid_argument(name + ": resolution must be >= 2 counts per revolution, got " +
                                std::to_string(counts));
  }
  if (!(sigma_w > 0.0) || !std::isfinite(sigma_w)) {
    throw std::invalid_argument(name + ": process noise must be > 0, got " +
                                std::to_string(sigma_w));
  }
  measurement_variance_ = quantisation_variance(counts);
  noise_density_ = sigma_w * sigma_w * std::pow(period_s, 2 * order + 1);

  // Steady state of the Riccati recursion at the nominal period; it converges
  // geometrically, within a few thousand steps for sensible parameters.
  P_steady_ = process_noise(1.0);
  for (int i = 0; i < 100000; ++i) {
    const Matrix previous = P_steady_;
    riccati_step(P_steady_, 1.0);
    if ((P_steady_ - previous).norm() <= 1e-13 * P_steady_.norm()) {
      break;
    }
  }
  P_ = P_steady_;
}

double IntegratorChain::quantisation_variance(double counts) {
  const double step_rad = 2.0 * std::numbers::pi / counts;
  return step_rad * step_rad / 12.0;
}

IntegratorChain::Matrix IntegratorChain::transition(double h) const {
  // F_ij = h^(j-i) / (j-i)! for i <= j <= order.
  const double powers[kStates] = {1.0, h, h * h, h * h * h, h * h * h * h};
  Matrix F = Matrix::Zero();
  for (int i = 0; i <= order_; ++i) {
    for (int j = i; j <= order_; ++j) {
      F(i, j) = powers[j - i] / kFactorial[j - i];
    }
  }
  return F;
}

IntegratorChain::Matrix IntegratorChain::process_noise(double h) const {
  // Q = s ∫_0^h φ(τ) φ(τ)^T dτ with φ_i(τ) = τ^(m-i)/(m-i)!, m the order:
  // Q_ij = s h^(2m-i-j+1) / ((m-i)! (m-j)! (2m-i-j+1)).
  const int m = order_;
  double powers[2 * kStates] = {1.0};
  for (int p = 1; p < 2 * kStates; ++p) {
    powers[p] = powers[p - 1] * h;
  }
  Matrix Q = Matrix::Zero();
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j <= m; ++j) {
      const int p = 2 * m - i - j + 1;
      Q(i, j) = noise_density_ * powers[p] / (kFactorial[m - i] * kFactorial[m - j] * p);
    }
  }
  return Q;
}

IntegratorChain::Vector IntegratorChain::riccati_step(Matrix& P, double h) const {
  const Matrix F = transition(h);
  P = F * P * F.transpose() + process_noise(h);
  // H = (1 0 … 0): S = P_00 + r and K = P's first column / S.
  const Vector K = P.col(0) / (P(0, 0) + measurement_variance_);
  P -= K * P.row(0);
  P = 0.5 * (P + P.transpose()).eval();  // keep it symmetric against rounding
  return K;
}

IntegratorChain::Vector IntegratorChain::steady_state_gain() const {
  Matrix P = P_steady_;
  Vector K = riccati_step(P, 1.0);
  for (int i = 0; i < kStates; ++i) {
    K(i) /= std::pow(period_s_, i);  // scaled units back to SI
  }
  return K;
}

}  // namespace wbi::estimation
