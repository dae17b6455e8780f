// split-kalman's stick anticipation: a joint that sticks at every velocity
// reversal (its acceleration drops for a few ms, as with Coulomb friction) is
// followed by the sticking bank; a joint that does not stick (a plain sine)
// keeps the non-sticking bank, with the same estimates as without
// anticipation; a stick that begins as the joint slows down and ends along a
// ramp is followed better with the early start and the shaped release than
// without; the bank's stick/slip/recover primitives; parameter errors name
// the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "estimation_helpers.hpp"
#include "wbi/estimation/acceleration_bank.hpp"
#include "wbi/estimation/split_kalman.hpp"

namespace wbi::estimation::test {
namespace {

constexpr double kStep = 2.0 * std::numbers::pi / 16384.0;  // 14-bit encoder
constexpr double kOmega = 2.0 * std::numbers::pi * 2.0;     // 2 Hz oscillation

double quantised(double q) { return kStep * std::round(q / kStep); }

double sign(double x) { return static_cast<double>((x > 0.0) - (x < 0.0)); }

// How the simulated joint sticks at a reversal: from the sign change (band 0)
// or from when it slows below `band` rad/s; 15 % of its acceleration kept for
// `hold_s`, then the rest returning with time constant `release_s` (0: at once).
struct Stick {
  double band = 0.0;
  double hold_s = 0.008;
  double release_s = 0.0;
};

// A 2 Hz, 0.3 rad oscillator q̈ = −ω² q that, when `sticks`, sticks at each
// velocity reversal as `stick` says. Integrated at 10 µs; returns the true
// acceleration at each 1 ms sample and feeds the quantised positions to every
// estimator.
struct StickingOscillator {
  bool sticks;
  Stick stick;
  double q = 0.3;
  double dq = 0.0;
  double since_stick_s = -1.0;  // time since the current stick began, < 0: none
  double reversed_from = 0.0;   // sign of dq before the last stick

  double kept() const {
    if (since_stick_s < 0.0) {
      return 1.0;
    }
    if (since_stick_s < stick.hold_s) {
      return 0.15;
    }
    return stick.release_s > 0.0
               ? 1.0 - 0.85 * std::exp(-(since_stick_s - stick.hold_s) / stick.release_s)
               : 1.0;
  }
  double acceleration() const { return kept() * -kOmega * kOmega * q; }
  // Advances one 1 ms sample.
  void advance() {
    constexpr double h = 1e-5;
    for (int i = 0; i < 100; ++i) {
      const double before = dq;
      dq += h * acceleration();
      q += h * dq;
      if (since_stick_s >= 0.0) {
        since_stick_s += h;
        if (since_stick_s > stick.hold_s + 6.0 * stick.release_s) {
          since_stick_s = -1.0;
        }
      }
      const bool slowing =
          stick.band > 0.0 && std::abs(dq) < stick.band && dq * acceleration() < 0.0;
      const bool crossed = before * dq < 0.0;
      if (sticks && since_stick_s < 0.0 && (slowing || crossed) &&
          sign(slowing ? dq : before) != reversed_from) {
        reversed_from = sign(slowing ? dq : before);
        since_stick_s = 0.0;
      }
    }
  }
};

struct Outcome {
  double rmse_ddq;
  double stick_weight;
};

// RMSE of ddq over seconds 2–4, and the final weight of the sticking bank.
Outcome run(const SplitKalmanParameters& params, bool sticks, const Stick& stick = {}) {
  SplitKalmanEstimator estimator(1, params);
  StickingOscillator joint{sticks, stick};
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

Outcome run(bool sticks, double stick_duration_s) {
  SplitKalmanParameters params;
  params.stick_duration_s = stick_duration_s;
  return run(params, sticks);
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

// The simulator's friction: the joint sticks once it slows below 0.01 rad/s,
// and its acceleration comes back over a few ms, not in one step.
TEST(StickAnticipation, EarlyStartAndShapedReleaseFollowARampingStick) {
  const Stick friction{0.01, 0.008, 0.004};
  const Outcome shaped = run(SplitKalmanParameters{}, true, friction);
  SplitKalmanParameters box;  // the stick from the sign change, released at once
  box.stick_velocity = 0.0;
  box.stick_release_s = 0.0;
  box.stick_duration_s = 0.010;
  const Outcome boxed = run(box, true, friction);
  EXPECT_GT(shaped.stick_weight, 0.9);
  EXPECT_LT(shaped.rmse_ddq, 0.8 * boxed.rmse_ddq)
      << "shaped " << shaped.rmse_ddq << ", box " << boxed.rmse_ddq;
}

// stick() keeps a fraction of each filter's acceleration; slip() sets a
// fraction of the acceleration at the stick, recover() adds to it.
TEST(StickAnticipation, BankScalesAndReturnsTheAccelerationItHadAtTheStick) {
  AccelerationBank bank("test", 1, AccelerationBankParameters{}, 1e-3);
  Eigen::VectorXd q(1);
  q(0) = 0.0;
  bank.start(q);
  const double a = 3.0;  // a parabola, which every filter of the bank follows exactly
  for (std::int64_t k = 1; k <= 3000; ++k) {
    const double t = 1e-3 * static_cast<double>(k);
    q(0) = 0.5 * a * t * t;
    bank.step(1e-3, q, std::exp(-1e-3 / 0.1));
  }
  ASSERT_NEAR(bank.acceleration(0), a, 1e-6);
  bank.stick(0, 0.2);
  EXPECT_NEAR(bank.acceleration(0), 0.2 * a, 1e-6);
  bank.slip(0, 0.5);
  EXPECT_NEAR(bank.acceleration(0), 0.5 * a, 1e-6);
  bank.recover(0, 0.25);
  EXPECT_NEAR(bank.acceleration(0), 0.75 * a, 1e-6);
  bank.recover(0, 0.25);
  EXPECT_NEAR(bank.acceleration(0), a, 1e-6);
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
  SplitKalmanParameters release;
  release.stick_release_s = -0.001;
  EXPECT_NE(message(release).find("stick-release must be >= 0 s"), std::string::npos);
  SplitKalmanParameters band;
  band.stick_velocity = -0.1;
  EXPECT_NE(message(band).find("stick-velocity must be >= 0 rad/s"), std::string::npos);
  SplitKalmanParameters memory;
  memory.stick_memory_s = 0.0;
  EXPECT_NE(message(memory).find("stick-memory must be > 0 s"), std::string::npos);
  EXPECT_THROW(make_estimator("split-kalman", 2, {{"stick-fraction", 2.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace wbi::estimation::test
