#include "accuracy.hpp"

#include <cmath>
#include <limits>

namespace wbi::bench {

void run_estimator(estimation::DerivativeEstimator& estimator, const EncoderRecording& recording,
                   Estimates& out) {
  const Eigen::Index samples = recording.q_measured.cols();
  out.dq.resize(estimator.joints(), samples);
  out.ddq.resize(estimator.joints(), samples);
  estimator.reset();
  for (Eigen::Index k = 0; k < samples; ++k) {
    estimator.update(recording.stamp_ns[static_cast<std::size_t>(k)], recording.q_measured.col(k));
    out.dq.col(k) = estimator.velocity();
    out.ddq.col(k) = estimator.acceleration();
  }
}

double shifted_rmse(const Motion& motion, const EncoderRecording& recording,
                    const Eigen::MatrixXd& estimate, Derivative derivative, double lag_s,
                    double warm_up_s) {
  double sum = 0.0;
  std::size_t count = 0;
  for (Eigen::Index k = 0; k < estimate.cols(); ++k) {
    const double t = 1e-9 * static_cast<double>(recording.stamp_ns[static_cast<std::size_t>(k)]);
    if (t < warm_up_s) {
      continue;
    }
    for (Eigen::Index j = 0; j < estimate.rows(); ++j) {
      double q = 0.0;
      double dq = 0.0;
      double ddq = 0.0;
      motion.evaluate(static_cast<int>(j), t - lag_s, q, dq, ddq);
      const double truth = derivative == Derivative::velocity ? dq : ddq;
      const double error = estimate(j, k) - truth;
      sum += error * error;
      ++count;
    }
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

Fit accuracy(const Motion& motion, const EncoderRecording& recording,
             const Eigen::MatrixXd& estimate, Derivative derivative, double warm_up_s) {
  const auto rmse_at = [&](double lag) {
    return shifted_rmse(motion, recording, estimate, derivative, lag, warm_up_s);
  };
  // Coarse grid, then golden-section search in the bracket around its minimum.
  double best_lag = 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (int ms = -5; ms <= 60; ++ms) {
    const double value = rmse_at(1e-3 * ms);
    if (value < best) {
      best = value;
      best_lag = 1e-3 * ms;
    }
  }
  double a = best_lag - 1e-3;
  double b = best_lag + 1e-3;
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - ratio * (b - a);
  double d = a + ratio * (b - a);
  double fc = rmse_at(c);
  double fd = rmse_at(d);
  while (b - a > 1e-5) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - ratio * (b - a);
      fc = rmse_at(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + ratio * (b - a);
      fd = rmse_at(d);
    }
  }
  return {rmse_at(0.0), 0.5 * (a + b)};
}

}  // namespace wbi::bench
