// A controller's reference input (reference_input.hpp) without DDS: points
// used at their stamp bit for bit, carried between points, waiting when ahead;
// the stale rules; what is refused, restarted, overwritten and counted; the
// lockstep waits; and no allocation per tick.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include <wbi/controllers/reference_input.hpp>
#include <wbi/types.hpp>

#include "allocation_counter.hpp"

namespace {

using wbi::controllers::ReferenceInput;
using wbi::controllers::ReferenceSpec;
using wbi::controllers::ReferenceStatus;
using wbi::controllers::StaleRule;
using wbi::controllers::TrajectoryPoint;

constexpr std::int64_t kMs = 1'000'000;  // ns

ReferenceSpec com_spec(StaleRule rule) {
  return {.name = "com", .unit = "m", .size = 3, .max_age_s = 0.05, .rule = rule, .decay_s = 0.5};
}

// A point at stamp_ns with position x, velocity v and acceleration a (3 values).
TrajectoryPoint point(std::int64_t stamp_ns, const Eigen::Vector3d& x,
                      const Eigen::Vector3d& v = Eigen::Vector3d::Zero(),
                      const Eigen::Vector3d& a = Eigen::Vector3d::Zero()) {
  TrajectoryPoint p;
  p.stamp_ns = stamp_ns;
  p.size = 3;
  for (int i = 0; i < 3; ++i) {
    p.position[i] = x[i];
    p.velocity[i] = v[i];
    p.acceleration[i] = a[i];
  }
  return p;
}

// The input with a measured value the test sets (what the controller measures).
struct Input {
  explicit Input(StaleRule rule) : input("balance/com", com_spec(rule)) {}
  ReferenceStatus at(std::int64_t time_ns) {
    return input.at(time_ns, [this]() -> const Eigen::VectorXd& { return measured; });
  }
  ReferenceInput input;
  Eigen::VectorXd measured = Eigen::Vector3d(0.0, 0.0, 0.8);
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(ReferenceInput, FreshPointBitForBitAtItsStamp) {
  Input in(StaleRule::hold_last);
  const Eigen::Vector3d x(0.1 / 3.0, -std::sqrt(2.0) * 1e-3, 0.79);
  const Eigen::Vector3d v(0.01, 0.2 / 7.0, 0.0);
  ASSERT_TRUE(in.input.push(point(1000 * kMs, x, v)));
  EXPECT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(in.input.position()[i], x[i]) << i;
    EXPECT_EQ(in.input.velocity()[i], v[i]) << i;
  }
  EXPECT_EQ(in.input.received(), 1u);
  EXPECT_EQ(in.input.carried_ticks(), 0u);
}

TEST(ReferenceInput, CarriedByVelocityAndAccelerationBetweenPoints) {
  Input in(StaleRule::hold_last);
  const Eigen::Vector3d x(0.0, 0.02, 0.8), v(0.1, -0.3, 0.0), a(1.0, 2.0, -0.5);
  in.input.push(point(1000 * kMs, x, v, a));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  const double dt = 0.02;
  ASSERT_EQ(in.at(1020 * kMs), ReferenceStatus::fresh);
  const Eigen::Vector3d expected = x + v * dt + 0.5 * dt * dt * a;
  EXPECT_LT((in.input.position() - expected).norm(), 1e-15);
  EXPECT_LT((in.input.velocity() - (v + dt * a)).norm(), 1e-15);
  EXPECT_EQ(in.input.acceleration(), a);
  EXPECT_EQ(in.input.carried_ticks(), 1u);
  EXPECT_EQ(in.input.stale_ticks(), 0u);
}

TEST(ReferenceInput, PointsAheadOfTimeWaitUntilDue) {
  Input in(StaleRule::hold_last);
  in.input.push(point(1000 * kMs, Eigen::Vector3d(0.0, 0.0, 0.8)));
  in.input.push(point(1010 * kMs, Eigen::Vector3d(0.0, 0.01, 0.8)));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  EXPECT_EQ(in.input.position().y(), 0.0) << "the 1.010 s point is not due at 1.000 s";
  ASSERT_EQ(in.at(1005 * kMs), ReferenceStatus::fresh);
  EXPECT_EQ(in.input.position().y(), 0.0) << "nor at 1.005 s (carried, at rest)";
  ASSERT_EQ(in.at(1010 * kMs), ReferenceStatus::fresh);
  EXPECT_EQ(in.input.position().y(), 0.01);
  EXPECT_EQ(in.input.carried_ticks(), 1u);
}

TEST(ReferenceInput, HoldLastHoldsThePositionAtRestWhenStale) {
  Input in(StaleRule::hold_last);
  const Eigen::Vector3d x(0.01, 0.05, 0.78);
  in.input.push(point(1000 * kMs, x, Eigen::Vector3d(0.0, 0.3, 0.0), Eigen::Vector3d(0, 1, 0)));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  ASSERT_EQ(in.at(1050 * kMs), ReferenceStatus::fresh) << "max_age_s is 0.05 s: still fresh";
  EXPECT_EQ(in.at(1051 * kMs), ReferenceStatus::stale);
  EXPECT_EQ(in.input.position(), x) << "the last position, not carried";
  EXPECT_TRUE(in.input.velocity().isZero());
  EXPECT_TRUE(in.input.acceleration().isZero());
  EXPECT_EQ(in.at(3000 * kMs), ReferenceStatus::stale);
  EXPECT_EQ(in.input.position(), x);
  EXPECT_EQ(in.input.stale_ticks(), 2u);
  EXPECT_EQ(in.input.stale_episodes(), 1u);
  EXPECT_EQ(in.input.missing_ticks(), 0u);
}

TEST(ReferenceInput, DecayToStateReachesOneOverEAfterDecayS) {
  Input in(StaleRule::decay_to_state);
  const Eigen::Vector3d x(0.0, 0.05, 0.8);
  in.measured = Eigen::Vector3d(0.0, -0.01, 0.78);
  in.input.push(point(1000 * kMs, x));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  // Stale from 1.060 s on: the decay starts at the last point's position.
  ASSERT_EQ(in.at(1060 * kMs), ReferenceStatus::stale);
  EXPECT_LT((in.input.position() - x).norm(), 1e-15);
  ASSERT_EQ(in.at(1560 * kMs), ReferenceStatus::stale);  // decay_s = 0.5 s later
  const Eigen::Vector3d gap = x - in.measured;
  const Eigen::Vector3d left = in.input.position() - in.measured;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(left[i], std::exp(-1.0) * gap[i], 1e-12) << i;
  }
  EXPECT_TRUE(in.input.velocity().isZero());
  ASSERT_EQ(in.at(11060 * kMs), ReferenceStatus::stale);  // 20 time constants
  EXPECT_LT((in.input.position() - in.measured).norm(), 1e-9) << "at the measured value";
  EXPECT_EQ(in.input.stale_episodes(), 1u);
}

TEST(ReferenceInput, FallBackThrowsNamingTheInputAndTheAge) {
  Input in(StaleRule::fall_back);
  in.input.push(point(1000 * kMs, Eigen::Vector3d(0.0, 0.0, 0.8)));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  try {
    in.at(1125 * kMs);
    FAIL() << "a stale fall_back input throws";
  } catch (const wbi::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("balance/com"), std::string::npos) << what;
    EXPECT_NE(what.find("0.125 s old"), std::string::npos) << what;
    EXPECT_NE(what.find("0.050 s"), std::string::npos) << "the bound: " << what;
  }
}

TEST(ReferenceInput, BeforeAnyPointTheMeasuredValue) {
  for (const StaleRule rule :
       {StaleRule::hold_last, StaleRule::decay_to_state, StaleRule::fall_back}) {
    Input in(rule);
    EXPECT_EQ(in.at(0), ReferenceStatus::missing) << to_string(rule);
    EXPECT_EQ(in.input.position(), in.measured) << to_string(rule);
    EXPECT_TRUE(in.input.velocity().isZero());
    EXPECT_EQ(in.at(kMs), ReferenceStatus::missing) << to_string(rule);
    EXPECT_EQ(in.input.missing_ticks(), 2u) << to_string(rule);
    EXPECT_EQ(in.input.stale_ticks(), 0u) << to_string(rule);
    EXPECT_EQ(in.input.stale_episodes(), 0u) << "missing is no stale episode";
  }
}

TEST(ReferenceInput, WrongSizeIsRefused) {
  Input in(StaleRule::hold_last);
  TrajectoryPoint two = point(1000 * kMs, Eigen::Vector3d(1.0, 1.0, 1.0));
  two.size = 2;
  EXPECT_FALSE(in.input.push(two));
  EXPECT_EQ(in.input.malformed(), 1u);
  EXPECT_EQ(in.input.received(), 0u);
  EXPECT_EQ(in.at(1000 * kMs), ReferenceStatus::missing) << "the refused point is not used";
}

TEST(ReferenceInput, OlderPointRestartsAndDropsTheQueue) {
  Input in(StaleRule::hold_last);
  in.input.push(point(1000 * kMs, Eigen::Vector3d(0.0, 0.01, 0.8)));
  in.input.push(point(2000 * kMs, Eigen::Vector3d(0.0, 0.02, 0.8)));
  in.input.push(point(3000 * kMs, Eigen::Vector3d(0.0, 0.03, 0.8)));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  // A new simulation (its time starts over): the queued 2 s and 3 s points
  // were the old run's.
  in.input.push(point(500 * kMs, Eigen::Vector3d(0.0, -0.01, 0.8)));
  EXPECT_EQ(in.input.restarts(), 1u);
  ASSERT_EQ(in.at(500 * kMs), ReferenceStatus::fresh);
  EXPECT_EQ(in.input.position().y(), -0.01);
  EXPECT_EQ(in.at(2000 * kMs), ReferenceStatus::stale) << "the old 2 s point was dropped";
  EXPECT_EQ(in.input.position().y(), -0.01);
  EXPECT_EQ(in.at(3000 * kMs), ReferenceStatus::stale) << "the old 3 s point was dropped";
  EXPECT_EQ(in.input.position().y(), -0.01);
}

TEST(ReferenceInput, FullQueueOverwritesTheOldest) {
  Input in(StaleRule::hold_last);
  const auto n = static_cast<std::int64_t>(ReferenceInput::kCapacity);
  for (std::int64_t k = 1; k <= n + 1; ++k) {
    ASSERT_TRUE(in.input.push(point(k * kMs, Eigen::Vector3d(0.0, 0.001 * k, 0.8))));
  }
  EXPECT_EQ(in.input.overwritten(), 1u);
  EXPECT_EQ(in.input.received(), static_cast<std::uint64_t>(n + 1));
  EXPECT_EQ(in.at(kMs), ReferenceStatus::missing) << "the 1 ms point was overwritten";
  ASSERT_EQ(in.at(2 * kMs), ReferenceStatus::fresh);
  EXPECT_EQ(in.input.position().y(), 0.001 * 2);
  ASSERT_EQ(in.at((n + 1) * kMs), ReferenceStatus::fresh);
  EXPECT_EQ(in.input.position().y(), 0.001 * static_cast<double>(n + 1));
}

TEST(ReferenceInput, OneStaleEpisodePerFreshToStaleTransition) {
  Input in(StaleRule::hold_last);
  const Eigen::Vector3d x(0.0, 0.0, 0.8);
  in.input.push(point(1000 * kMs, x));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  for (std::int64_t t = 1100; t <= 1300; t += 100) {
    ASSERT_EQ(in.at(t * kMs), ReferenceStatus::stale);
  }
  EXPECT_EQ(in.input.stale_episodes(), 1u);
  in.input.push(point(1400 * kMs, x));
  ASSERT_EQ(in.at(1400 * kMs), ReferenceStatus::fresh);
  ASSERT_EQ(in.at(1500 * kMs), ReferenceStatus::stale);
  ASSERT_EQ(in.at(1600 * kMs), ReferenceStatus::stale);
  EXPECT_EQ(in.input.stale_episodes(), 2u);
  EXPECT_EQ(in.input.stale_ticks(), 5u);
}

TEST(ReferenceInput, WaitForAPointFromAnotherThread) {
  Input in(StaleRule::hold_last);
  std::thread generator([&] { in.input.push(point(1000 * kMs, Eigen::Vector3d(0, 0, 0.8))); });
  EXPECT_TRUE(in.input.wait_for(1000 * kMs, 10'000 * kMs));
  generator.join();
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(in.input.wait_for(1001 * kMs, 100 * kMs)) << "no point for 1.001 s";
  EXPECT_GE(seconds_since(start), 0.1);
}

// Lockstep (set_wait): a tick waits for its point; once a wait timed out (the
// generator died), the next ticks do not wait until a point comes again: a
// dead generator costs one timeout, not one per tick.
TEST(ReferenceInput, LockstepWaitsOnceForADeadGenerator) {
  Input in(StaleRule::decay_to_state);
  constexpr std::int64_t kWait = 400 * kMs;
  in.input.set_wait(kWait);
  in.input.push(point(1000 * kMs, Eigen::Vector3d(0, 0, 0.8)));
  ASSERT_EQ(in.at(1000 * kMs), ReferenceStatus::fresh);
  // A point that comes while the tick waits is this tick's.
  std::thread generator([&] { in.input.push(point(1001 * kMs, Eigen::Vector3d(0, 0.001, 0.8))); });
  ASSERT_EQ(in.at(1001 * kMs), ReferenceStatus::fresh);
  generator.join();
  EXPECT_EQ(in.input.position().y(), 0.001);
  EXPECT_EQ(in.input.carried_ticks(), 0u);
  EXPECT_EQ(in.input.late(), 0u);

  auto start = std::chrono::steady_clock::now();
  in.at(1002 * kMs);
  EXPECT_GE(seconds_since(start), 0.4) << "the first tick without a point waits";
  EXPECT_EQ(in.input.late(), 1u);
  // 9 ticks after a timeout: none waits. A tick that waited here would time
  // out (no point comes) and count as late: late() staying 1 proves it,
  // without timing the ticks (how fast a tick runs is not this test's).
  for (std::int64_t t = 1003; t <= 1010; ++t) {
    in.at(t * kMs);
  }
  in.at(1100 * kMs);
  EXPECT_EQ(in.input.late(), 1u) << "the dead generator is late once";
  EXPECT_EQ(in.input.stale_ticks(), 1u) << "1.100 s: stale";

  // It comes back: the ticks wait for it again.
  in.input.push(point(1200 * kMs, Eigen::Vector3d(0, 0, 0.8)));
  ASSERT_EQ(in.at(1200 * kMs), ReferenceStatus::fresh);
  start = std::chrono::steady_clock::now();
  in.at(1201 * kMs);
  EXPECT_GE(seconds_since(start), 0.4) << "a fed input waits again";
  EXPECT_EQ(in.input.late(), 2u);
}

TEST(ReferenceInput, AtAllocatesNothing) {
  for (const StaleRule rule : {StaleRule::hold_last, StaleRule::decay_to_state}) {
    Input in(rule);
    in.at(0);  // missing: the measured value
    in.input.push(point(1000 * kMs, Eigen::Vector3d(0, 0.01, 0.8), Eigen::Vector3d(0, 0.1, 0),
                        Eigen::Vector3d(0, 1, 0)));
    in.input.push(point(1020 * kMs, Eigen::Vector3d(0, 0.02, 0.8)));
    const long before = wbi::test::thread_allocation_count();
    in.at(999 * kMs);   // missing
    in.at(1000 * kMs);  // fresh at the stamp
    in.at(1010 * kMs);  // carried
    in.at(1020 * kMs);  // fresh
    in.at(1100 * kMs);  // stale
    in.at(1600 * kMs);  // stale, decayed
    EXPECT_EQ(wbi::test::thread_allocation_count() - before, 0) << to_string(rule);
    EXPECT_EQ(in.input.stale_ticks(), 2u);
  }
}

}  // namespace
