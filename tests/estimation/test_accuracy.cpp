// A guard on the benchmark's headline result (bench/estimation has the full
// table): on a quantised 1 Hz sine the Kalman estimator has at most half the
// RMSE of the original adaptive window, for velocity and for acceleration; so
// has split-kalman.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "estimation_helpers.hpp"

namespace wbi::estimation::test {
namespace {

struct Rmse {
  double dq = 0.0;
  double ddq = 0.0;
};

Rmse rmse_on_quantised_sine(const std::string& method) {
  constexpr int kJoints = 8;
  const double step = 2.0 * std::numbers::pi / 16384.0;  // 14-bit encoder
  const double w = 2.0 * std::numbers::pi;               // 1 Hz, 0.4 rad
  const auto estimator = make_estimator(method, kJoints);
  Eigen::VectorXd q(kJoints);
  double sum_dq = 0.0;
  double sum_ddq = 0.0;
  int count = 0;
  for (std::int64_t k = 0; k < 3000; ++k) {
    const double t = seconds(stamp_at(k));
    for (int j = 0; j < kJoints; ++j) {
      const double phase = 2.0 * std::numbers::pi * j / kJoints;
      q(j) = step * std::round(0.4 * std::sin(w * t + phase) / step);
    }
    estimator->update(stamp_at(k), q);
    if (t < 0.5) {
      continue;
    }
    for (int j = 0; j < kJoints; ++j) {
      const double phase = 2.0 * std::numbers::pi * j / kJoints;
      const double e_dq = estimator->velocity()(j) - 0.4 * w * std::cos(w * t + phase);
      const double e_ddq = estimator->acceleration()(j) + 0.4 * w * w * std::sin(w * t + phase);
      sum_dq += e_dq * e_dq;
      sum_ddq += e_ddq * e_ddq;
      ++count;
    }
  }
  return {std::sqrt(sum_dq / count), std::sqrt(sum_ddq / count)};
}

TEST(Accuracy, SplitKalmanHalvesTheAdaptiveWindowError) {
  const Rmse window = rmse_on_quantised_sine("adaptive-window");
  const Rmse split = rmse_on_quantised_sine("split-kalman");
  EXPECT_LE(split.dq, 0.5 * window.dq) << "adaptive-window " << window.dq;
  EXPECT_LE(split.ddq, 0.5 * window.ddq) << "adaptive-window " << window.ddq;
}

TEST(Accuracy, KalmanHalvesTheAdaptiveWindowError) {
  const Rmse window = rmse_on_quantised_sine("adaptive-window");
  const Rmse kalman = rmse_on_quantised_sine("kalman");
  EXPECT_LE(kalman.dq, 0.5 * window.dq) << "adaptive-window " << window.dq;
  EXPECT_LE(kalman.ddq, 0.5 * window.ddq) << "adaptive-window " << window.ddq;
}

}  // namespace
}  // namespace wbi::estimation::test
