// split-kalman's stick anticipation: a joint that sticks at every velocity
// reversal (its acceleration drops for a few ms, as with Coulomb friction) is
// followed by the sticking bank; a joint that does not stick (a plain sine)
// keeps the non-sticking bank, with the same estimates as without
// anticipation; parameter errors name the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "estimation_helpers.hpp"
#include "wbi/estimation/split_kalman.hpp"

namespace wbi::estimation::test {
namespace {

constexpr double kStep = 2.0 * std::numbers::pi / 16384.0;  // 14-bit encoder
constexpr double kOmega = 2.0 * std::numbers::pi * 2.0;     // 2 Hz oscillation

double quantised(double q) { return kStep * std::round(q / kStep); }

// A 2 Hz, 0.3 rad oscillator q̈ = −ω² q that, when `sticks`, keeps only 15 %
// of its acceleration for 8 ms after each velocity reversal. Integrated at
// 10 µs; returns the true acceleration at each 1 ms sample and feeds the
// quantised positions to every estimator.
struct StickingOscillator {
  bool sticks;
  double q = 0.3;
  double dq = 0.0;
  double stuck_s = 0.0;  // time left in the current stick

  double acceleration() const { return (stuck_s > 0.0 ? 0.15 : 1.0) * -kOmega * kOmega * q; }
  // Advances one 1 ms sample.
  void advance() {
    constexpr double h = 1e-5;
    for (int i = 0; i < 100; ++i) {
      const double before = dq;
      dq += h * acceleration();
      q += h * dq;
      stuck_s = std::max(0.0, stuck_s - h);
      if (sticks && before * dq < 0.0) {
        stuck_s = 0.008;
      }
    }
  }
};

struct Outcome {
  double rmse_ddq;
  double stick_weight;
};

// RMSE of ddq over seconds 2–4, and the final weight of the sticking bank.
Outcome run(bool sticks, double stick_duration_s) {
  SplitKalmanParameters params;
  params.stick_duration_s = stick_duration_s;
  SplitKalmanEstimator estimator(1, params);
  StickingOscillator joint{sticks};
  Eigen::VectorXd q(1);
  double sum = 0.0;
  int count = 0;
  for (std::int64_t k = 0; k < 4000; ++k) {
    q(0) = quantised(joint.q);
    estimator.update(stamp_at(k), q);
    if (k >= 2000) {
      const double error = estimator.acceleration()(0) - joint.acceleration();
      sum += error * error;
      ++count;
    }
    joint.advance();
  }
  return {std::sqrt(sum / count), estimator.stick_weights()(0)};
}

TEST(StickAnticipation, FollowsAJointThatSticksAtReversals) {
  const Outcome anticipating = run(true, 0.008);
  const Outcome plain = run(true, 0.0);
  EXPECT_GT(anticipating.stick_weight, 0.9);
  EXPECT_LT(anticipating.rmse_ddq, 0.6 * plain.rmse_ddq)
      << "with anticipation " << anticipating.rmse_ddq << ", without " << plain.rmse_ddq;
  EXPECT_EQ(plain.stick_weight, 0.0);
}

TEST(StickAnticipation, KeepsTheMovingBankWhenNothingSticks) {
  const Outcome anticipating = run(false, 0.008);
  const Outcome plain = run(false, 0.0);
  EXPECT_LT(anticipating.stick_weight, 0.01);
  EXPECT_LT(anticipating.rmse_ddq, 1.05 * plain.rmse_ddq)
      << "with anticipation " << anticipating.rmse_ddq << ", without " << plain.rmse_ddq;
}

TEST(StickAnticipation, BadParametersNameTheParameter) {
  const auto message = [](const SplitKalmanParameters& params) {
    try {
      SplitKalmanEstimator estimator(2, params);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SplitKalmanParameters fraction;
  fraction.stick_fraction = 1.5;
  EXPECT_NE(message(fraction).find("stick-fraction must be in [0, 1]"), std::string::npos);
  SplitKalmanParameters duration;
  duration.stick_duration_s = -0.001;
  EXPECT_NE(message(duration).find("stick-duration must be >= 0 s"), std::string::npos);
  SplitKalmanParameters memory;
  memory.stick_memory_s = 0.0;
  EXPECT_NE(message(memory).find("stick-memory must be > 0 s"), std::string::npos);
  EXPECT_THROW(make_estimator("split-kalman", 2, {{"stick-fraction", 2.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace wbi::estimation::test
