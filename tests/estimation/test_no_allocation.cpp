// update() of every estimator and of the low-pass allocates nothing.
// This file and the library sources are compiled with EIGEN_RUNTIME_NO_MALLOC
// (see CMakeLists.txt), so any Eigen heap allocation inside the checked region
// asserts; the replaced operator new (tests/support/allocation_counter) also
// counts every other heap allocation.
#ifndef EIGEN_RUNTIME_NO_MALLOC
#error "this test must be built with EIGEN_RUNTIME_NO_MALLOC"
#endif

#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.hpp"
#include "wbi/estimation/estimator_factory.hpp"
#include "wbi/estimation/low_pass_filter.hpp"
#include "wbi/estimation/model_kalman.hpp"

namespace wbi::estimation {
namespace {

constexpr Eigen::Index kJoints = 32;

// Runs `body` with Eigen's allocation check on; returns the operator-new count.
template <typename Body>
long allocations_during(Body body) {
  const long before = wbi::test::allocation_count();
  Eigen::internal::set_is_malloc_allowed(false);
  body();
  Eigen::internal::set_is_malloc_allowed(true);
  return wbi::test::allocation_count() - before;
}

TEST(NoAllocation, EveryEstimatorUpdate) {
  for (const auto& method : method_names()) {
    const auto estimator = make_estimator(method, kJoints);
    Eigen::VectorXd q(kJoints);
    Eigen::VectorXd bad = Eigen::VectorXd::Constant(kJoints, std::nan(""));
    const long count = allocations_during([&] {
      for (std::int64_t k = 0; k < 3000; ++k) {
        for (Eigen::Index j = 0; j < kJoints; ++j) {
          q(j) = 0.3 * std::sin(0.004 * static_cast<double>(k * (j + 1)));
        }
        // Regular samples, plus every kind of anomaly on the way.
        const std::int64_t stamp = k * 1'000'000 + (k % 5 == 4 ? 1'000'000 : 0);
        estimator->update(stamp, q);
        if (k % 97 == 0) {
          estimator->update(stamp, q);              // duplicated
          estimator->update(stamp - 2'000'000, q);  // out of order
          estimator->update(stamp + 10, bad);       // non-finite
        }
        if (k == 2000) {
          estimator->reset();
        }
      }
    });
    EXPECT_EQ(count, 0) << method;
    EXPECT_GT(estimator->stamp_counters().dropped, 0u) << method;
  }
}

TEST(NoAllocation, ModelKalmanWithItsInput) {
  ModelKalmanEstimator fused(kJoints, {});
  Eigen::VectorXd q(kJoints);
  Eigen::VectorXd input(kJoints);
  Eigen::VectorXd bad = Eigen::VectorXd::Constant(kJoints, std::nan(""));
  const long count = allocations_during([&] {
    for (std::int64_t k = 0; k < 3000; ++k) {
      for (Eigen::Index j = 0; j < kJoints; ++j) {
        q(j) = 0.3 * std::sin(0.004 * static_cast<double>(k * (j + 1)));
      }
      fused.update(k * 1'000'000, q);
      input = -0.000016 * q;
      fused.set_model_acceleration(k % 97 == 0 ? bad : input);
    }
  });
  EXPECT_EQ(count, 0);
  EXPECT_GT(fused.non_finite_inputs(), 0u);
}

TEST(NoAllocation, LowPassUpdate) {
  LowPassFilter filter(6, 20.0);
  Eigen::VectorXd wrench(6);
  const long count = allocations_during([&] {
    for (std::int64_t k = 0; k < 1000; ++k) {
      wrench.setConstant(static_cast<double>(k % 10));
      filter.update(k * 1'000'000, wrench);
    }
  });
  EXPECT_EQ(count, 0);
}

}  // namespace
}  // namespace wbi::estimation
