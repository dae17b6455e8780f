// Response to a position step: finite, of the right sign, settled afterwards;
// and the exact step response of the first-order low-pass.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "estimation_helpers.hpp"
#include "wbi/estimation/low_pass_filter.hpp"

namespace wbi::estimation::test {
namespace {

TEST(StepResponse, EveryMethodStaysFiniteAndSettles) {
  const double height = 0.1;  // rad, at t = 0.5 s
  const auto step = [&](double t) { return t >= 0.5 ? height : 0.0; };
  for (const auto& method : all_methods()) {
    const auto estimator = make_estimator(method, 2);
    double peak_velocity = 0.0;
    Eigen::VectorXd q(2);
    for (std::int64_t k = 0; k < 2000; ++k) {
      q.setConstant(step(seconds(stamp_at(k))));
      estimator->update(stamp_at(k), q);
      ASSERT_TRUE(estimator->velocity().allFinite()) << method << " at sample " << k;
      ASSERT_TRUE(estimator->acceleration().allFinite()) << method << " at sample " << k;
      peak_velocity = std::max(peak_velocity, estimator->velocity()(0));
      if (k < 500) {
        ASSERT_EQ(estimator->velocity()(0), 0.0) << method << ": moved before the step";
      }
    }
    // A forward step gives a positive velocity pulse, no larger than the
    // backward difference's height/period.
    EXPECT_GT(peak_velocity, 0.0) << method;
    EXPECT_LE(peak_velocity, height / 1e-3 + 1e-9) << method;
    // 1.5 s after the step the estimates are back to rest.
    EXPECT_NEAR(estimator->velocity()(0), 0.0, 1e-6) << method;
    EXPECT_NEAR(estimator->acceleration()(0), 0.0, 1e-4) << method;
  }
}

TEST(StepResponse, LowPassFollowsTheExponential) {
  const double cutoff = 5.0;
  LowPassFilter filter(1, cutoff);
  Eigen::VectorXd x(1);
  x << 0.0;
  filter.update(0, x);
  x << 1.0;
  for (std::int64_t k = 1; k <= 300; ++k) {
    // Irregular intervals: the discretisation is exact for any interval.
    const std::int64_t stamp = stamp_at(k) + (k % 2) * 300'000;
    filter.update(stamp, x);
    const double expected = 1.0 - std::exp(-2.0 * std::numbers::pi * cutoff * seconds(stamp));
    ASSERT_NEAR(filter.value()(0), expected, 1e-12) << "sample " << k;
  }
}

TEST(StepResponse, LowPassWithZeroCutoffPassesThrough) {
  LowPassFilter filter(3, 0.0);
  const Eigen::Vector3d a(1.0, -2.0, 3.0);
  const Eigen::Vector3d b(4.0, 5.0, -6.0);
  filter.update(0, a);
  filter.update(stamp_at(1), b);
  EXPECT_EQ(filter.value(), b);
}

}  // namespace
}  // namespace wbi::estimation::test
