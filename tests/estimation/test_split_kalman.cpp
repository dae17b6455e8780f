// split-kalman: exact derivatives of polynomials (the blend of exact filters is
// exact), the multiple-model weights choosing the quiet filter for a slow
// joint and the agile one for a fast joint, the loop-safe velocity low-pass,
// and parameter errors. Stamps, reset, sizes, steps and allocation are
// covered for every method by the other files.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "estimation_helpers.hpp"
#include "wbi/estimation/split_kalman.hpp"

namespace wbi::estimation::test {
namespace {

// q = 0.1 + 0.5 t + 1.5 t² - 0.8 t³: dq = 0.5 + 3 t - 2.4 t², ddq = 3 - 4.8 t
double cubic(double t) { return 0.1 + 0.5 * t + 1.5 * t * t - 0.8 * t * t * t; }

class SplitKalmanStamps : public ::testing::TestWithParam<bool> {
 protected:
  std::vector<std::int64_t> stamps(std::int64_t n) const {
    return GetParam() ? irregular_stamps(n) : regular_stamps(n);
  }
};

TEST_P(SplitKalmanStamps, ConvergesToExactDerivativesOfCubics) {
  SplitKalmanEstimator estimator(3, {});
  const auto s = stamps(3000);
  feed(estimator, s, cubic);
  const double t = seconds(s.back());
  for (Eigen::Index j = 0; j < 3; ++j) {
    const double scale = static_cast<double>(j + 1);
    EXPECT_NEAR(estimator.velocity()(j), scale * (0.5 + 3.0 * t - 2.4 * t * t), 1e-6 * scale);
    EXPECT_NEAR(estimator.acceleration()(j), scale * (3.0 - 4.8 * t), 1e-5 * scale);
    EXPECT_NEAR(estimator.acceleration_weights().col(j).sum(), 1.0, 1e-12);
  }
}

TEST_P(SplitKalmanStamps, LoopSafeVelocityIsExactForLines) {
  // The loop-safe settings of README.md: order 2, wide bandwidth, 30 Hz low-pass.
  SplitKalmanParameters params;
  params.velocity_order = 2;
  params.velocity_process_noise = 3000.0;
  params.velocity_cutoff_hz = 30.0;
  SplitKalmanEstimator estimator(2, params);
  feed(estimator, stamps(1500), [](double t) { return 0.3 + 1.7 * t; });
  EXPECT_NEAR(estimator.velocity()(0), 1.7, 1e-6);
  EXPECT_NEAR(estimator.velocity()(1), 3.4, 1e-6);
  EXPECT_NEAR(estimator.acceleration()(1), 0.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Stamps, SplitKalmanStamps, ::testing::Values(false, true),
                         [](const auto& param_info) {
                           return param_info.param ? "Irregular" : "Regular";
                         });

TEST(SplitKalman, WeightsFollowTheMotion) {
  // Joint 0 creeps (0.05 rad/s, mostly quantisation), joint 1 waves at 5 Hz, 0.1 rad.
  SplitKalmanEstimator estimator(2, {});
  const double step = 2.0 * std::numbers::pi / 16384.0;
  Eigen::VectorXd q(2);
  for (std::int64_t k = 0; k < 2000; ++k) {
    const double t = seconds(stamp_at(k));
    q(0) = step * std::round(0.05 * t / step);
    q(1) = step * std::round(0.1 * std::sin(2.0 * std::numbers::pi * 5.0 * t) / step);
    estimator.update(stamp_at(k), q);
  }
  const Eigen::MatrixXd& w = estimator.acceleration_weights();
  ASSERT_EQ(w.rows(), 4);
  EXPECT_GT(w(0, 0), 0.5) << "the creeping joint should follow the quiet filter\n" << w;
  EXPECT_GT(w(3, 1), 0.5) << "the waving joint should follow the agile filter\n" << w;
}

TEST(SplitKalman, OneModelIsThePlainKalmanFilter) {
  // A bank of one with the velocity filter's settings gives the kalman method's output.
  const auto split = make_estimator("split-kalman", 2,
                                    {{"acceleration-models", 1.0},
                                     {"acceleration-noise-min", 300.0},
                                     {"acceleration-noise-max", 300.0}});
  const auto kalman = make_estimator("kalman", 2);
  const auto wave = [](double t) { return 0.2 * std::sin(2.0 * std::numbers::pi * 2.0 * t); };
  feed(*split, regular_stamps(700), wave);
  feed(*kalman, regular_stamps(700), wave);
  EXPECT_TRUE(split->velocity().isApprox(kalman->velocity(), 1e-12));
  EXPECT_TRUE(split->acceleration().isApprox(kalman->acceleration(), 1e-12));
}

TEST(SplitKalman, BadParametersNameTheParameter) {
  const auto message = [](const Parameters& given) {
    try {
      make_estimator("split-kalman", 2, given);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"acceleration-noise-min", 500.0}, {"acceleration-noise-max", 100.0}})
                .find("acceleration-noise-max must be >= acceleration-noise-min"),
            std::string::npos);
  EXPECT_NE(message({{"acceleration-models", 0.0}}).find("'acceleration-models'"),
            std::string::npos);
  EXPECT_NE(message({{"velocity-cutoff", -1.0}}).find("'velocity-cutoff'"), std::string::npos);
  EXPECT_NE(message({{"velocity-order", 5.0}}).find("'velocity-order'"), std::string::npos);
  EXPECT_NE(message({{"acceleration-memory", 0.0}}).find("'acceleration-memory'"),
            std::string::npos);
}

}  // namespace
}  // namespace wbi::estimation::test
