// Exact derivatives of polynomials, for every method whose model contains them.
#include <gtest/gtest.h>

#include "estimation_helpers.hpp"
#include "wbi/estimation/adaptive_window.hpp"
#include "wbi/estimation/backward_difference.hpp"
#include "wbi/estimation/kalman_derivative.hpp"

namespace wbi::estimation::test {
namespace {

// q = 0.3 + 1.7 t (per joint times j+1)
double line(double t) { return 0.3 + 1.7 * t; }
// q = 0.3 + 1.7 t - 2.5 t²: dq = 1.7 - 5 t, ddq = -5
double parabola(double t) { return 0.3 + 1.7 * t - 2.5 * t * t; }
// q = 0.1 + 0.5 t + 1.5 t² - 0.8 t³: dq = 0.5 + 3 t - 2.4 t², ddq = 3 - 4.8 t
double cubic(double t) { return 0.1 + 0.5 * t + 1.5 * t * t - 0.8 * t * t * t; }

void expect_rates(const DerivativeEstimator& estimator, double dq, double ddq, double tolerance) {
  for (Eigen::Index j = 0; j < estimator.joints(); ++j) {
    const double scale = static_cast<double>(j + 1);
    EXPECT_NEAR(estimator.velocity()(j), scale * dq, tolerance * scale) << "joint " << j;
    EXPECT_NEAR(estimator.acceleration()(j), scale * ddq, tolerance * scale) << "joint " << j;
  }
}

class StampPattern : public ::testing::TestWithParam<bool> {
 protected:
  std::vector<std::int64_t> stamps(std::int64_t n) const {
    return GetParam() ? irregular_stamps(n) : regular_stamps(n);
  }
};

TEST_P(StampPattern, BackwardDifferenceIsExactForLinesAndParabolas) {
  BackwardDifferenceEstimator estimator(3, {});
  const auto s = stamps(40);
  feed(estimator, s, line);
  expect_rates(estimator, 1.7, 0.0, 1e-9);
  estimator.reset();
  feed(estimator, s, parabola);
  // Backward difference is the velocity at the last interval's midpoint.
  const double t = seconds(s.back());
  const double dt = seconds(s.back() - s[s.size() - 2]);
  expect_rates(estimator, 1.7 - 5.0 * (t - 0.5 * dt), -5.0, 1e-6);
}

TEST_P(StampPattern, AdaptiveWindowIsExactForLinesAndParabolas) {
  AdaptiveWindowEstimator estimator(3, {});
  const auto s = stamps(60);
  feed(estimator, s, line);
  expect_rates(estimator, 1.7, 0.0, 1e-9);
  estimator.reset();
  feed(estimator, s, parabola);
  // The linear fit is not exact for a parabola; the quadratic one is.
  for (Eigen::Index j = 0; j < estimator.joints(); ++j) {
    EXPECT_NEAR(estimator.acceleration()(j), -5.0 * static_cast<double>(j + 1), 1e-6);
  }
}

TEST_P(StampPattern, KalmanConvergesToExactDerivativesOfCubics) {
  KalmanEstimator estimator(3, {});
  const auto s = stamps(3000);
  feed(estimator, s, cubic);
  const double t = seconds(s.back());
  expect_rates(estimator, 0.5 + 3.0 * t - 2.4 * t * t, 3.0 - 4.8 * t, 1e-6);
}

TEST_P(StampPattern, ConstantAccelerationKalmanIsExactForParabolas) {
  KalmanParameters params;
  params.model_order = 2;
  params.process_noise = 100.0;
  KalmanEstimator estimator(2, params);
  const auto s = stamps(3000);
  feed(estimator, s, parabola);
  const double t = seconds(s.back());
  expect_rates(estimator, 1.7 - 5.0 * t, -5.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Stamps, StampPattern, ::testing::Values(false, true),
                         [](const auto& param_info) {
                           return param_info.param ? "Irregular" : "Regular";
                         });

TEST(Polynomials, EveryMethodGivesZeroForAConstant) {
  for (const auto& method : all_methods()) {
    const auto estimator = make_estimator(method, 4);
    feed(*estimator, regular_stamps(100), [](double) { return 0.7; });
    EXPECT_EQ(estimator->velocity().cwiseAbs().maxCoeff(), 0.0) << method;
    EXPECT_EQ(estimator->acceleration().cwiseAbs().maxCoeff(), 0.0) << method;
  }
}

}  // namespace
}  // namespace wbi::estimation::test
