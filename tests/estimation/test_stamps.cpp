// Bad source stamps: duplicated, out-of-order, non-increasing, dropped, long
// gaps and non-finite positions are counted, never give NaN or a jump.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "estimation_helpers.hpp"
#include "wbi/estimation/low_pass_filter.hpp"

namespace wbi::estimation::test {
namespace {

double smooth(double t) { return 0.4 * std::sin(2.0 * std::numbers::pi * 1.3 * t); }

// Largest sample-to-sample change of the velocity estimate of joint 0 over a
// stamp sequence (anomalies included, each fed with the true position).
struct StreamRun {
  double largest_velocity_change = 0.0;
  double largest_acceleration_change = 0.0;
  Eigen::VectorXd final_velocity;
};

StreamRun run(DerivativeEstimator& estimator, const std::vector<std::int64_t>& stamps) {
  StreamRun out;
  Eigen::VectorXd q(estimator.joints());
  double previous_dq = 0.0;
  double previous_ddq = 0.0;
  for (const std::int64_t stamp : stamps) {
    q.setConstant(smooth(seconds(stamp)));
    estimator.update(stamp, q);
    EXPECT_TRUE(estimator.velocity().allFinite());
    EXPECT_TRUE(estimator.acceleration().allFinite());
    if (seconds(stamp) > 0.2) {  // after start-up
      out.largest_velocity_change =
          std::max(out.largest_velocity_change, std::abs(estimator.velocity()(0) - previous_dq));
      out.largest_acceleration_change = std::max(
          out.largest_acceleration_change, std::abs(estimator.acceleration()(0) - previous_ddq));
    }
    previous_dq = estimator.velocity()(0);
    previous_ddq = estimator.acceleration()(0);
  }
  out.final_velocity = estimator.velocity();
  return out;
}

TEST(Stamps, DuplicatedAndOlderStampsAreCountedAndIgnored) {
  for (const auto& method : all_methods()) {
    const auto estimator = make_estimator(method, 2);
    std::vector<std::int64_t> stamps = regular_stamps(1000);
    const StreamRun clean = run(*estimator, stamps);
    estimator->reset();
    // Same stream with anomalies inserted: repeats and stale samples.
    std::vector<std::int64_t> bad;
    for (std::size_t k = 0; k < stamps.size(); ++k) {
      bad.push_back(stamps[k]);
      if (k % 50 == 10) {
        bad.push_back(stamps[k]);  // duplicated
      }
      if (k % 50 == 20) {
        bad.push_back(stamps[k - 3]);  // out of order
      }
      if (k % 50 == 30) {
        bad.push_back(stamps[k] - 500'000);  // older than the last, never seen
      }
    }
    const StreamRun dirty = run(*estimator, bad);
    const StampCounters& counters = estimator->stamp_counters();
    EXPECT_EQ(counters.duplicated, 20u) << method;
    EXPECT_EQ(counters.out_of_order, 40u) << method;
    EXPECT_EQ(counters.non_increasing(), 60u) << method;
    EXPECT_EQ(counters.dropped, 0u) << method;
    // Ignored samples change nothing: same result as the clean stream, no extra jump.
    EXPECT_EQ(dirty.final_velocity, clean.final_velocity) << method;
    EXPECT_LE(dirty.largest_velocity_change, clean.largest_velocity_change) << method;
    EXPECT_LE(dirty.largest_acceleration_change, clean.largest_acceleration_change) << method;
  }
}

TEST(Stamps, DroppedSamplesAreCountedWithoutAJump) {
  for (const auto& method : all_methods()) {
    const auto estimator = make_estimator(method, 2);
    const StreamRun clean = run(*estimator, regular_stamps(1000));
    const auto clean_counters = estimator->stamp_counters();
    estimator->reset();
    estimator->reset_counters();
    std::vector<std::int64_t> stamps;
    for (std::int64_t k = 0; k < 1000; ++k) {
      if (k % 100 != 50 && (k < 600 || k > 602)) {  // single drops, and one run of three
        stamps.push_back(stamp_at(k));
      }
    }
    const StreamRun dropped = run(*estimator, stamps);
    EXPECT_EQ(clean_counters.dropped, 0u);
    EXPECT_EQ(estimator->stamp_counters().dropped, 13u) << method;
    EXPECT_EQ(estimator->stamp_counters().gaps, 0u) << method;
    // The real interval is used: the estimate moves no more than a few
    // clean steps' worth across a drop.
    EXPECT_LE(dropped.largest_velocity_change, 4.0 * clean.largest_velocity_change + 1e-3)
        << method;
  }
}

TEST(Stamps, LongGapRestartsTheEstimator) {
  for (const auto& method : all_methods()) {
    const auto estimator = make_estimator(method, 1, {{"max-gap", 0.05}});
    Eigen::VectorXd q(1);
    for (std::int64_t k = 0; k < 100; ++k) {
      q << 0.01 * static_cast<double>(k);
      estimator->update(stamp_at(k), q);
    }
    q << 5.0;
    EXPECT_EQ(estimator->update(stamp_at(300), q), SampleStatus::after_gap) << method;
    EXPECT_EQ(estimator->stamp_counters().gaps, 1u) << method;
    EXPECT_EQ(estimator->velocity()(0), 0.0) << method;
    EXPECT_EQ(estimator->acceleration()(0), 0.0) << method;
    EXPECT_EQ(estimator->update(stamp_at(301), q), SampleStatus::accepted) << method;
    EXPECT_EQ(estimator->velocity()(0), 0.0) << method;  // at rest since the restart
  }
}

TEST(Stamps, NonFinitePositionsAreCountedAndIgnored) {
  for (const auto& method : all_methods()) {
    const auto estimator = make_estimator(method, 2);
    feed(*estimator, regular_stamps(100), smooth);
    const Eigen::VectorXd dq = estimator->velocity();
    Eigen::VectorXd q(2);
    q << std::numeric_limits<double>::quiet_NaN(), 0.0;
    EXPECT_EQ(estimator->update(stamp_at(100), q), SampleStatus::non_finite) << method;
    q << std::numeric_limits<double>::infinity(), 0.0;
    EXPECT_EQ(estimator->update(stamp_at(101), q), SampleStatus::non_finite) << method;
    EXPECT_EQ(estimator->stamp_counters().non_finite, 2u) << method;
    EXPECT_EQ(estimator->velocity(), dq) << method;
    // The stamp of an ignored sample is not consumed: the next sample is accepted.
    q.setConstant(smooth(0.1));
    EXPECT_EQ(estimator->update(stamp_at(100), q), SampleStatus::accepted) << method;
  }
}

TEST(Stamps, LowPassCountsAndIgnoresBadStamps) {
  LowPassFilter filter(1, 10.0);
  Eigen::VectorXd x(1);
  x << 1.0;
  EXPECT_EQ(filter.update(stamp_at(0), x), SampleStatus::first);
  x << 2.0;
  EXPECT_EQ(filter.update(stamp_at(1), x), SampleStatus::accepted);
  const double value = filter.value()(0);
  x << 100.0;
  EXPECT_EQ(filter.update(stamp_at(1), x), SampleStatus::duplicated);
  EXPECT_EQ(filter.update(stamp_at(0), x), SampleStatus::out_of_order);
  EXPECT_EQ(filter.value()(0), value);
  EXPECT_EQ(filter.stamp_counters().non_increasing(), 2u);
  EXPECT_EQ(filter.update(stamp_at(4), x), SampleStatus::accepted);
  EXPECT_EQ(filter.stamp_counters().dropped, 2u);
}

TEST(Stamps, MonitorClassifiesEachCase) {
  StampMonitor monitor(1000.0, 0.1);
  double dt = -1.0;
  EXPECT_EQ(monitor.check(5'000'000, dt), SampleStatus::first);
  EXPECT_EQ(dt, 0.0);
  EXPECT_EQ(monitor.check(6'000'000, dt), SampleStatus::accepted);
  EXPECT_DOUBLE_EQ(dt, 1e-3);
  EXPECT_EQ(monitor.check(6'000'000, dt), SampleStatus::duplicated);
  EXPECT_EQ(monitor.check(5'500'000, dt), SampleStatus::out_of_order);
  EXPECT_EQ(monitor.check(9'000'000, dt), SampleStatus::accepted);
  EXPECT_EQ(monitor.counters().dropped, 2u);
  EXPECT_EQ(monitor.check(200'000'000, dt), SampleStatus::after_gap);
  EXPECT_EQ(monitor.counters().gaps, 1u);
  EXPECT_EQ(monitor.counters().accepted, 4u);
  EXPECT_THROW(StampMonitor(0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(StampMonitor(1000.0, 0.001), std::invalid_argument);
}

}  // namespace
}  // namespace wbi::estimation::test
