// model-kalman: the encoders fused with a model's acceleration. On a quantised
// multi-sine up to 19 Hz, with a model that is 5 % off in gain, offset and
// drifting, and noisy, its acceleration error is at most half the adaptive
// window's, without lag (issue 38's target); the encoders remove the model's
// slow errors; with an exact model the error is a small fraction of the
// signal; without a model it is `kalman`.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "estimation_helpers.hpp"
#include "wbi/estimation/kalman_derivative.hpp"
#include "wbi/estimation/model_kalman.hpp"

namespace wbi::estimation::test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kStep = kTwoPi / 16384.0;  // 14-bit encoder

// q(t) = Σ A sin(2π f t + φ): accelerations of 6-19 rad/s² per component.
struct Sine {
  double amplitude, hz, phase;
};
const std::vector<Sine> kTrajectory = {
    {0.3, 0.7, 0.0}, {0.05, 3.1, 1.0}, {0.004, 11.0, 2.0}, {0.0005, 19.0, 0.5}};

double position(double t) {
  double q = 0.0;
  for (const auto& s : kTrajectory) {
    q += s.amplitude * std::sin(kTwoPi * s.hz * t + s.phase);
  }
  return q;
}

double acceleration(double t) {
  double a = 0.0;
  for (const auto& s : kTrajectory) {
    const double w = kTwoPi * s.hz;
    a -= s.amplitude * w * w * std::sin(w * t + s.phase);
  }
  return a;
}

// How the model predicts the acceleration.
struct ModelError {
  double gain = 1.0;    // multiplies the true acceleration
  double offset = 0.0;  // rad/s²
  double drift = 0.0;   // rad/s², amplitude of a 0.3 Hz sine
  double noise = 0.0;   // rad/s², standard deviation of white noise
};

struct Trace {
  std::vector<double> estimate;  // ddq per sample
  std::vector<double> truth;
  std::vector<double> model;  // the model's acceleration given (fused only)
};

// Feeds the quantised trajectory for 5 s at 1 kHz to `estimator`; `fused`, when
// it is the estimator, gets the model's acceleration at each sample, after it.
Trace trace_of(DerivativeEstimator& estimator, ModelKalmanEstimator* fused = nullptr,
               const ModelError& model = {}) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, model.noise);
  Eigen::VectorXd q(1);
  Eigen::VectorXd u(1);
  Trace out;
  for (std::int64_t k = 0; k < 5000; ++k) {
    const double t = seconds(stamp_at(k));
    q[0] = kStep * std::round(position(t) / kStep);
    estimator.update(stamp_at(k), q);
    if (fused != nullptr) {
      u[0] = model.gain * acceleration(t) + model.offset +
             model.drift * std::sin(kTwoPi * 0.3 * t) + noise(random);
      fused->set_model_acceleration(u);
      out.model.push_back(u[0]);
    }
    out.estimate.push_back(estimator.acceleration()[0]);
    out.truth.push_back(acceleration(t));
  }
  return out;
}

// RMS of estimate[k] − truth[k − delay] after the first second.
double rmse(const std::vector<double>& estimate, const std::vector<double>& truth, int delay = 0) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t k = 1000; k < estimate.size(); ++k) {
    const double e = estimate[k] - truth[k - static_cast<std::size_t>(delay)];
    sum += e * e;
    ++count;
  }
  return std::sqrt(sum / count);
}

double rmse(const Trace& r, int delay = 0) { return rmse(r.estimate, r.truth, delay); }

// The delay (samples) that best aligns the estimate with the truth.
int lag(const Trace& r) {
  int best = 0;
  for (int d = 1; d <= 30; ++d) {
    if (rmse(r, d) < rmse(r, best)) {
      best = d;
    }
  }
  return best;
}

// 5 % gain error, offset, drift and noise: a model whose error reaches 19 Hz.
const ModelError kRealisticModel{1.05, 0.5, 0.5, 0.3};

TEST(ModelKalman, HalvesTheAdaptiveWindowErrorWithAnImperfectModel) {
  const auto window = make_estimator("adaptive-window", 1);
  ModelKalmanEstimator fused(1, {});
  const Trace w = trace_of(*window);
  const Trace m = trace_of(fused, &fused, kRealisticModel);
  EXPECT_LE(rmse(m), 0.5 * rmse(w)) << "adaptive-window " << rmse(w);
  EXPECT_EQ(lag(m), 0) << "adaptive-window's lag " << lag(w) << " samples";
}

TEST(ModelKalman, TheEncodersCorrectTheModelsSlowErrors) {
  ModelKalmanEstimator fused(1, {});
  const Trace m = trace_of(fused, &fused, {1.0, 0.5, 0.5, 0.3});  // offset, drift and noise
  EXPECT_LE(rmse(m), 0.7 * rmse(m.model, m.truth)) << "the model alone";
}

TEST(ModelKalman, ExactModelIsFollowedWithoutLag) {
  ModelKalmanEstimator fused(1, {});
  const Trace m = trace_of(fused, &fused);
  double rms = 0.0;
  for (std::size_t k = 1000; k < m.truth.size(); ++k) {
    rms += m.truth[k] * m.truth[k];
  }
  rms = std::sqrt(rms / static_cast<double>(m.truth.size() - 1000));
  EXPECT_LE(rmse(m), 0.02 * rms) << "signal rms " << rms;
  EXPECT_EQ(lag(m), 0);
}

TEST(ModelKalman, WithoutInputItIsKalman) {
  ModelKalmanParameters params;
  KalmanEstimator kalman(3, {params.model_order, params.resolution_counts, params.process_noise});
  ModelKalmanEstimator fused(3, params);
  const auto stamps = irregular_stamps(2000);
  feed(kalman, stamps, position);
  feed(fused, stamps, position);
  EXPECT_EQ(fused.velocity(), kalman.velocity());
  EXPECT_EQ(fused.acceleration(), kalman.acceleration());
}

TEST(ModelKalman, NonFiniteInputKeepsTheLastAndIsCounted) {
  ModelKalmanEstimator a(2, {});
  ModelKalmanEstimator b(2, {});
  const Eigen::Vector2d u(3.0, -1.0);
  a.set_model_acceleration(u);
  b.set_model_acceleration(u);
  b.set_model_acceleration(Eigen::Vector2d(std::nan(""), INFINITY));
  EXPECT_EQ(b.non_finite_inputs(), 2u);
  const auto stamps = regular_stamps(200);
  feed(a, stamps, position);
  feed(b, stamps, position);
  EXPECT_EQ(a.acceleration(), b.acceleration());
  EXPECT_TRUE(b.acceleration().allFinite());
}

TEST(ModelKalman, BadInputIsNamed) {
  ModelKalmanEstimator fused(3, {});
  try {
    fused.set_model_acceleration(Eigen::VectorXd::Zero(2));
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "model-kalman: the model acceleration has 2 values, expected 3");
  }
}

}  // namespace
}  // namespace wbi::estimation::test
