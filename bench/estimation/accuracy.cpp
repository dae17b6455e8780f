#include "accuracy.hpp"

#include <algorithm>
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

SampleMask near_velocity_reversals(const EncoderRecording& recording, double before_s,
                                   double after_s) {
  const Eigen::MatrixXd& dq = recording.dq_true;
  const auto seconds = [&](Eigen::Index k) {
    return 1e-9 * static_cast<double>(recording.stamp_ns[static_cast<std::size_t>(k)]);
  };
  SampleMask mask = SampleMask::Constant(dq.rows(), dq.cols(), false);
  for (Eigen::Index j = 0; j < dq.rows(); ++j) {
    for (Eigen::Index k = 1; k < dq.cols(); ++k) {
      if ((dq(j, k - 1) > 0.0) == (dq(j, k) > 0.0)) {
        continue;
      }
      // Reversal at t_k: mark every sample in [t_k − before, t_k + after].
      const double t = seconds(k);
      for (Eigen::Index i = k; i >= 0 && seconds(i) >= t - before_s; --i) {
        mask(j, i) = true;
      }
      for (Eigen::Index i = k; i < dq.cols() && seconds(i) <= t + after_s; ++i) {
        mask(j, i) = true;
      }
    }
  }
  return mask;
}

double rmse_outside(const EncoderRecording& recording, const Eigen::MatrixXd& estimate,
                    const Eigen::MatrixXd& truth, const SampleMask& excluded, double warm_up_s) {
  double sum = 0.0;
  std::size_t count = 0;
  for (Eigen::Index k = 0; k < estimate.cols(); ++k) {
    if (1e-9 * static_cast<double>(recording.stamp_ns[static_cast<std::size_t>(k)]) < warm_up_s) {
      continue;
    }
    for (Eigen::Index j = 0; j < estimate.rows(); ++j) {
      if (!excluded(j, k)) {
        const double error = estimate(j, k) - truth(j, k);
        sum += error * error;
        ++count;
      }
    }
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

Estimates truth_blind_to_jumps(const EncoderRecording& recording, double jump, int blind) {
  Estimates out{recording.dq_true, recording.ddq_true};
  const Eigen::MatrixXd& ddq = recording.ddq_true;
  for (Eigen::Index j = 0; j < ddq.rows(); ++j) {
    for (Eigen::Index k = 1; k < ddq.cols(); ++k) {
      if (std::abs(ddq(j, k) - ddq(j, k - 1)) <= jump) {
        continue;
      }
      // Blind for `blind` samples: the value before the jump is kept.
      const Eigen::Index end = std::min<Eigen::Index>(k + blind, ddq.cols());
      for (Eigen::Index i = k; i < end; ++i) {
        out.ddq(j, i) = ddq(j, k - 1);
      }
      k = end - 1;
    }
  }
  return out;
}

}  // namespace wbi::bench
