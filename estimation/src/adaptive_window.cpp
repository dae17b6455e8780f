#include "wbi/estimation/adaptive_window.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wbi::estimation {

AdaptiveWindowEstimator::AdaptiveWindowEstimator(Eigen::Index joints,
                                                 const AdaptiveWindowParameters& params,
                                                 const StreamParameters& stream)
    : DerivativeEstimator(joints, stream), params_(params) {
  if (params.velocity_window < 2) {
    throw std::invalid_argument("adaptive-window: velocity-window must be >= 2 samples, got " +
                                std::to_string(params.velocity_window));
  }
  if (params.acceleration_window < 3) {
    throw std::invalid_argument("adaptive-window: acceleration-window must be >= 3 samples, got " +
                                std::to_string(params.acceleration_window));
  }
  if (!(params.threshold_rad > 0.0) || !std::isfinite(params.threshold_rad)) {
    throw std::invalid_argument("adaptive-window: threshold must be > 0 rad, got " +
                                std::to_string(params.threshold_rad));
  }
  capacity_ = std::max(params.velocity_window, params.acceleration_window);
  q_history_ = Eigen::MatrixXd::Zero(capacity_, joints);
  dt_history_ = Eigen::VectorXd::Zero(capacity_);
  tau_ = Eigen::VectorXd::Zero(capacity_);
  y_ = Eigen::VectorXd::Zero(capacity_);
  linear_inverse_.assign(static_cast<std::size_t>(capacity_ + 1), Eigen::Matrix2d::Zero());
  quadratic_inverse_.assign(static_cast<std::size_t>(capacity_ + 1), Eigen::Matrix3d::Zero());
}

void AdaptiveWindowEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  count_ = 0;
  push(0.0, q);
}

void AdaptiveWindowEstimator::push(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q) {
  newest_ = (newest_ + 1) % capacity_;
  q_history_.row(newest_) = q.transpose();
  dt_history_(newest_) = dt_s;
  count_ = std::min(count_ + 1, capacity_);
}

void AdaptiveWindowEstimator::update_fit_matrices() {
  // tau_i = t_(k-i) - t_k in nominal periods (well-conditioned normal equations).
  const double rate = sample_rate_hz();
  tau_(0) = 0.0;
  for (Eigen::Index i = 1; i < count_; ++i) {
    const Eigen::Index later = (newest_ - (i - 1) + capacity_) % capacity_;
    tau_(i) = tau_(i - 1) - dt_history_(later) * rate;
  }
  // Power sums s_p = sum_i tau_i^p over the n newest samples, grown with n.
  double s[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  for (Eigen::Index n = 1; n <= count_; ++n) {
    const double t = tau_(n - 1);
    double power = 1.0;
    for (double& sum : s) {
      sum += power;
      power *= t;
    }
    if (n >= 2) {
      Eigen::Matrix2d normal;
      normal << s[0], s[1], s[1], s[2];
      linear_inverse_[static_cast<std::size_t>(n)] = normal.inverse();
    }
    if (n >= 3) {
      Eigen::Matrix3d normal;
      normal << s[0], s[1], s[2], s[1], s[2], s[3], s[2], s[3], s[4];
      quadratic_inverse_[static_cast<std::size_t>(n)] = normal.inverse();
    }
  }
}

double AdaptiveWindowEstimator::linear_slope(const Eigen::VectorXd& y) const {
  const Eigen::Index longest = std::min<Eigen::Index>(params_.velocity_window, count_);
  double slope = 0.0;
  double sum_y = 0.0;
  double sum_ty = 0.0;
  for (Eigen::Index n = 1; n <= longest; ++n) {
    sum_y += y(n - 1);
    sum_ty += tau_(n - 1) * y(n - 1);
    if (n < 2) {
      continue;
    }
    // Least-squares line y = a + b tau over the n newest samples.
    const Eigen::Vector2d ab =
        linear_inverse_[static_cast<std::size_t>(n)] * Eigen::Vector2d(sum_y, sum_ty);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (std::abs(y(i) - ab(0) - ab(1) * tau_(i)) > params_.threshold_rad) {
        return slope;  // window n breaks the threshold: keep the longest one that did not
      }
    }
    slope = ab(1);
  }
  return slope;
}

double AdaptiveWindowEstimator::quadratic_curvature(const Eigen::VectorXd& y) const {
  const Eigen::Index longest = std::min<Eigen::Index>(params_.acceleration_window, count_);
  double curvature = 0.0;
  double sum_y = 0.0;
  double sum_ty = 0.0;
  double sum_tty = 0.0;
  for (Eigen::Index n = 1; n <= longest; ++n) {
    const double t = tau_(n - 1);
    sum_y += y(n - 1);
    sum_ty += t * y(n - 1);
    sum_tty += t * t * y(n - 1);
    if (n < 3) {
      continue;
    }
    // Least-squares parabola y = a + b tau + c tau² over the n newest samples.
    const Eigen::Vector3d abc =
        quadratic_inverse_[static_cast<std::size_t>(n)] * Eigen::Vector3d(sum_y, sum_ty, sum_tty);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double ti = tau_(i);
      if (std::abs(y(i) - abc(0) - (abc(1) + abc(2) * ti) * ti) > params_.threshold_rad) {
        return curvature;
      }
    }
    curvature = abc(2);
  }
  return curvature;
}

void AdaptiveWindowEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                                   Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  push(dt_s, q);
  update_fit_matrices();
  const double rate = sample_rate_hz();
  for (Eigen::Index j = 0; j < joints(); ++j) {
    // Positions relative to the newest one, newest first: keeps the sums small.
    for (Eigen::Index i = 0; i < count_; ++i) {
      y_(i) = q_history_((newest_ - i + capacity_) % capacity_, j) - q(j);
    }
    dq(j) = linear_slope(y_) * rate;
    // A parabola needs three samples; until then the acceleration stays zero.
    ddq(j) = count_ >= 3 ? 2.0 * quadratic_curvature(y_) * rate * rate : 0.0;
  }
}

}  // namespace wbi::estimation
