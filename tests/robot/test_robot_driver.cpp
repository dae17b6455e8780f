// The driver component (wbi/robot/robot_driver.hpp) over a toy backend: two
// unit-inertia joints. Commands in POSITION mode move them; a bad command is
// counted on the status; a sensors-only instance never powers the backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/robot/robot_driver.hpp>
#include <wbi/runtime/runner.hpp>

#include "two_joint_toy.hpp"

namespace {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;

std::uint64_t counter(const wbi::msg::ComponentStatus& status, const std::string& name) {
  for (const auto& c : status.counters()) {
    if (c.name().to_string() == name) {
      return c.value();
    }
  }
  return 0;
}

struct Driver {
  wbi::dds::Participant participant{"driver_test"};
  wbi::runtime::SystemClock clock;
  std::unique_ptr<wbi::runtime::ComponentRunner> runner;

  explicit Driver(const std::string& parameters) {
    wbi::runtime::Registry registry;
    wbi::robot::register_driver(registry, "toy_robot", [](const wbi::runtime::Parameters&) {
      return std::make_unique<wbi::test::TwoJointToyBackend>();
    });
    wbi::runtime::RunnerOptions options;
    options.rate_hz = 500.0;
    options.status_period_s = 0.05;
    runner = std::make_unique<wbi::runtime::ComponentRunner>(
        registry.create("toy_robot"),
        wbi::runtime::ComponentContext{"toy", "toy_robot", &participant, &clock}, options);
    runner->configure(wbi::runtime::Parameters::from_string(parameters));
    runner->activate();
  }
};

TEST(RobotDriver, CommandsMoveTheJointsAndBadOnesAreCounted) {
  Driver driver("robot: toy_a\n");
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(driver.participant, topics::sensors("toy_a"),
                                                       qos::kStream);
  wbi::dds::Subscriber<wbi::msg::ComponentStatus> status(driver.participant, topics::kStatus,
                                                         qos::kStatus);
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(driver.participant,
                                                          topics::commands("toy_a"), qos::kCommand);
  ASSERT_TRUE(commands.wait_for_subscribers(1, 10s));
  wbi::msg::ActuatorCommand command;
  command.header().robot("toy_a");
  command.controller("test");
  command.joints({0, 1});
  command.modes({wbi::msg::POSITION, wbi::msg::POSITION});
  command.references({0.5, -0.3});
  commands.publish(command);
  wbi::dds::Received<wbi::msg::SensorSample> sample;
  const auto deadline = std::chrono::steady_clock::now() + 15s;
  while (std::chrono::steady_clock::now() < deadline &&
         !(sensors.wait_newer(sample, sample.count, 1s) &&
           std::abs(sample.sample.encoder_position()[0] - 0.5) < 0.01 &&
           std::abs(sample.sample.encoder_position()[1] + 0.3) < 0.01)) {
  }
  EXPECT_NEAR(sample.sample.encoder_position()[0], 0.5, 0.01);
  EXPECT_NEAR(sample.sample.encoder_position()[1], -0.3, 0.01);
  EXPECT_GT(sample.sample.header().seq(), 0u);

  command.joints({7});
  command.modes({wbi::msg::POSITION});
  command.references({0.0});
  commands.publish(command);
  wbi::dds::Received<wbi::msg::ComponentStatus> got;
  const auto status_deadline = std::chrono::steady_clock::now() + 10s;
  while (
      std::chrono::steady_clock::now() < status_deadline &&
      !(status.wait_newer(got, got.count, 1s) && counter(got.sample, "rejected_commands") == 1)) {
  }
  EXPECT_EQ(counter(got.sample, "rejected_commands"), 1u);
  EXPECT_EQ(counter(got.sample, "rejected_from/test"), 1u);  // per sender
  EXPECT_EQ(got.sample.last_error(),
            "command from 'test' rejected: joint index 7 out of range (the robot has 2 joints)");

  // beyond the position limit (2 rad): accepted, clamped, counted
  command.joints({1});
  command.references({5.0});
  commands.publish(command);
  // gains for a joint the robot does not have: refused, nothing applied
  wbi::dds::Publisher<wbi::msg::ControlParameters> parameters(
      driver.participant, topics::control_parameters("toy_a"), qos::kCommand);
  ASSERT_TRUE(parameters.wait_for_subscribers(1, 10s));
  wbi::msg::ControlParameters gains;
  gains.header().robot("toy_a");
  gains.controller("test");
  gains.joints({0, 9});
  gains.kp({1.0, 1.0});
  parameters.publish(gains);
  const auto more_deadline = std::chrono::steady_clock::now() + 10s;
  while (std::chrono::steady_clock::now() < more_deadline &&
         !(status.wait_newer(got, got.count, 1s) && counter(got.sample, "limit_clamps") == 1 &&
           counter(got.sample, "rejected_parameters") == 1)) {
  }
  EXPECT_EQ(counter(got.sample, "limit_clamps"), 1u);
  EXPECT_EQ(counter(got.sample, "rejected_parameters"), 1u);
  EXPECT_EQ(counter(got.sample, "rejected_from/test"), 2u);
  EXPECT_EQ(got.sample.last_error(),
            "control parameters from 'test' rejected: joint index 9 out of range (the robot has "
            "2 joints)");
  driver.runner->shutdown();
}

// POSITION through DDS into the driver (issue 26): a target streamed at 200 Hz
// arrives as fast as the same target sent once (each a 0.5 rad move at the
// default 0.5 rad/s: a 1.875 s minimum-jerk trajectory).
TEST(RobotDriver, StreamedPositionTargetArrivesLikeOneCommand) {
  Driver driver("robot: toy_stream\n");
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(driver.participant,
                                                       topics::sensors("toy_stream"), qos::kStream);
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(
      driver.participant, topics::commands("toy_stream"), qos::kCommand);
  ASSERT_TRUE(commands.wait_for_subscribers(1, 10s));
  wbi::msg::ActuatorCommand command;
  command.header().robot("toy_stream");
  command.controller("test");
  command.joints({0});
  command.modes({wbi::msg::POSITION});
  wbi::dds::Received<wbi::msg::SensorSample> sample;
  // Robot time (the samples' stamps) from the newest sample when the first
  // command goes out until joint a is within 10 mrad of `target`: the robot's
  // own clock, so that how late this thread is woken does not count (a CI run
  // under load measured 5.3 % apart on wall time).
  // `stall_ms`: the longest the driver's loop stopped during the move, from the
  // samples read (their stamps advance beyond their ticks, 2 ms each at 500 Hz).
  double stall_ms = 0.0;
  const auto move = [&](double target, bool stream) {
    command.references({target});
    const auto start = std::chrono::steady_clock::now();
    auto next = start;
    const std::int64_t start_ns = sample.sample.header().stamp_ns();
    std::int64_t last_ns = start_ns;
    std::uint64_t last_seq = sample.sample.header().seq();
    stall_ms = 0.0;
    commands.publish(command);
    while (std::chrono::steady_clock::now() - start < 10s) {
      if (stream && std::chrono::steady_clock::now() >= next) {
        commands.publish(command);
        next += 5ms;  // 200 Hz
      }
      if (!sensors.wait_newer(sample, sample.count, 5ms)) {
        continue;
      }
      const auto& header = sample.sample.header();
      stall_ms = std::max(stall_ms, 1e-6 * static_cast<double>(header.stamp_ns() - last_ns) -
                                        2.0 * static_cast<double>(header.seq() - last_seq));
      last_ns = header.stamp_ns();
      last_seq = header.seq();
      if (std::abs(sample.sample.encoder_position()[0] - target) < 0.01) {
        return 1e-9 * static_cast<double>(sample.sample.header().stamp_ns() - start_ns);
      }
    }
    return std::numeric_limits<double>::infinity();
  };
  // The first move is a warm-up: it arrived about 45 ms later than every later
  // one, sent once or streamed (the first samples on a new writer).
  move(0.5, false);
  // A stall of the driver's loop (ticks skipped) holds the last torque while
  // the trajectory goes on by the clock, and so moves the arrival either way: a
  // CI run under load measured 1.60 s once and 1.46 s streamed, and three 0.1 s
  // stops of this process make a streamed move arrive in 0.92 s. That is the
  // loop's stall, not streaming: a pair met by one over 20 ms is measured again
  // (three pairs at most).
  double once = 0.0, streamed = 0.0;
  for (int pair = 0; pair < 3; ++pair) {
    once = move(0.0, false);
    const double once_stall_ms = stall_ms;
    streamed = move(0.5, true);
    std::cout << "[measured] driver over DDS, POSITION 0.5 rad: once " << once
              << " s, streamed at 200 Hz " << streamed << " s; the loop's longest stall "
              << once_stall_ms << " and " << stall_ms << " ms\n";
    if (std::max(once_stall_ms, stall_ms) <= 20.0) {
      break;
    }
  }
  EXPECT_LT(once, 2.5);
  EXPECT_NEAR(streamed, once, 0.05 * once);
  driver.runner->shutdown();
}

TEST(RobotDriver, UnknownSideIsNamed) {
  wbi::dds::Participant participant("driver_test_sides");
  wbi::runtime::SystemClock clock;
  wbi::runtime::Registry registry;
  wbi::robot::register_driver(registry, "toy_robot", [](const wbi::runtime::Parameters&) {
    return std::make_unique<wbi::test::TwoJointToyBackend>();
  });
  wbi::runtime::ComponentRunner runner(registry.create("toy_robot"),
                                       {"toy", "toy_robot", &participant, &clock});
  EXPECT_THROW(runner.configure(wbi::runtime::Parameters::from_string(
                   "robot: toy_b\nsides: [sensors, motors]\n", "toy.yaml")),
               wbi::runtime::TransitionError);
  EXPECT_NE(runner.last_error().find("unknown side 'motors'"), std::string::npos)
      << runner.last_error();
}

}  // namespace
