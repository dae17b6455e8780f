// The Kalman estimator's model: its steady-state gain matches the documented
// bandwidth, and the discretisation is consistent across interval lengths.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wbi/estimation/integrator_chain.hpp"
#include "wbi/estimation/kalman_derivative.hpp"

namespace wbi::estimation::test {
namespace {

TEST(KalmanModel, BandwidthFollowsResolutionRateAndProcessNoise) {
  // README: ω_c ≈ (σ_w² / (r T))^(1/8) for order 3, and the last gain of a
  // 4th-order Butterworth-like filter is ω_c⁴ T.
  for (const double counts : {4096.0, 16384.0, 262144.0}) {
    const double sigma_w = 300.0;
    const double T = 1e-3;
    const KalmanEstimator estimator(1, {3, counts, sigma_w});
    const double step = 2.0 * std::numbers::pi / counts;
    const double r = step * step / 12.0;
    const double predicted = std::pow(sigma_w * sigma_w / (r * T), 1.0 / 8.0);
    const double from_gain = std::pow(estimator.model().steady_state_gain()(3) / T, 0.25);
    EXPECT_NEAR(from_gain / predicted, 1.0, 0.1) << counts << " counts";
  }
}

TEST(KalmanModel, TwoHalfStepsMakeOneStep) {
  const IntegratorChain chain("kalman", 3, 16384.0, 300.0, 1e-3);
  const IntegratorChain::Matrix half = chain.transition(0.5);
  EXPECT_TRUE((half * half).isApprox(chain.transition(1.0), 1e-14));
}

TEST(KalmanModel, StartsInSteadyState) {
  IntegratorChain chain("kalman", 3, 16384.0, 300.0, 1e-3);
  const IntegratorChain::Vector first = chain.step(1.0);
  for (int i = 0; i < 100; ++i) {
    chain.step(1.0);
  }
  EXPECT_TRUE(chain.step(1.0).isApprox(first, 1e-9));
}

}  // namespace
}  // namespace wbi::estimation::test
