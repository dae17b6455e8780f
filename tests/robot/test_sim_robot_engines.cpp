// Engines by name (wbi/sim_robot/engine_registry.hpp): a third engine, a toy
// registered in the test alone, runs in the one robot loop in lockstep — the
// sensor samples, the clock and the ground truth are its own, stamped with its
// time, one tick per answered command — and an unknown engine is one line
// listing the registered ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/runtime/runner.hpp>
#include <wbi/sim_robot/sim_robot.hpp>

#include "toy_engine.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::kDt;
using wbi::test::registry_with_toy;
using wbi::test::Seen;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;

constexpr std::size_t kTicks = 50;

TEST(SimRobotEngines, AnUnknownEngineIsOneLineListingTheRegisteredOnes) {
  wbi::dds::Participant participant("engines_unknown");
  wbi::runtime::SystemClock clock;
  Seen seen;
  const auto registry = registry_with_toy(seen);
  wbi::runtime::ComponentRunner runner(registry.create("sim_robot"),
                                       {"sim", "sim_robot", &participant, &clock});
  EXPECT_THROW(runner.configure(wbi::runtime::Parameters::from_string(
                   "robot: toy_unknown\nconfig: toy.cfg\nengine: bullet\n", "component 'sim'")),
               wbi::runtime::TransitionError);
  // the built-in engines (wbi, and mujoco when built with MuJoCo) and the toy, sorted
  auto names = wbi::sim_robot::builtin_engines().names();
  names.push_back("toy");
  std::sort(names.begin(), names.end());
  std::string registered;
  for (const auto& name : names) {
    registered += (registered.empty() ? "" : ", ") + name;
  }
  EXPECT_EQ(
      runner.last_error(),
      "<string>:3: component 'sim': unknown engine 'bullet' (registered: " + registered + ")");
  EXPECT_TRUE(seen.robot.empty()) << "no engine was built";
}

TEST(SimRobotEngines, AThirdEngineRunsInLockstepByRegistrationAlone) {
  wbi::dds::Participant participant("engines_lockstep");
  wbi::runtime::SystemClock clock;
  Seen seen;
  const auto registry = registry_with_toy(seen);
  wbi::runtime::ComponentRunner runner(registry.create("sim_robot"),
                                       {"sim", "sim_robot", &participant, &clock});
  runner.configure(wbi::runtime::Parameters::from_string(
      "{robot: toy_lockstep, engine: toy, config: toy.cfg, lockstep: true,"
      " lockstep_controllers: [test]}"));
  EXPECT_EQ(seen.robot, "toy_lockstep");
  EXPECT_EQ(seen.config, "toy.cfg");  // from a string: nothing to resolve against

  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(participant, topics::sensors("toy_lockstep"),
                                                       qos::kStream);
  wbi::dds::Subscriber<wbi::msg::SimulationClock> sim_clock(participant, topics::kClock,
                                                            qos::kStream);
  wbi::dds::Subscriber<wbi::msg::GroundTruth> truth(
      participant, topics::ground_truth("toy_lockstep"), qos::kStream);
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(
      participant, topics::commands("toy_lockstep"), qos::kCommand);
  ASSERT_TRUE(sensors.wait_for_publishers(1, 10s));
  ASSERT_TRUE(sim_clock.wait_for_publishers(1, 10s));
  ASSERT_TRUE(truth.wait_for_publishers(1, 10s));
  ASSERT_TRUE(commands.wait_for_subscribers(1, 10s));
  runner.activate();

  wbi::msg::ActuatorCommand command;
  command.header().robot("toy_lockstep");
  command.controller("test");
  command.joints({0});
  command.modes({wbi::msg::TORQUE});
  command.references({2.0});
  double q = 0.0;  // the toy's state, integrated here as the engine does
  double v = 0.0;
  wbi::dds::Received<wbi::msg::SensorSample> sample;
  wbi::dds::Received<wbi::msg::SimulationClock> tick;
  wbi::dds::Received<wbi::msg::GroundTruth> state;
  for (std::uint64_t k = 0; k < kTicks; ++k) {
    // Tick k is out, and the simulation waits for its command.
    ASSERT_TRUE(sensors.wait_newer(sample, sample.count, 10s)) << "tick " << k;
    ASSERT_TRUE(sim_clock.wait_newer(tick, tick.count, 10s)) << "tick " << k;
    ASSERT_TRUE(truth.wait_newer(state, state.count, 10s)) << "tick " << k;
    ASSERT_EQ(sample.sample.header().seq(), k);
    EXPECT_EQ(sample.sample.header().stamp_ns(), static_cast<std::int64_t>(k) * 1'000'000);
    EXPECT_EQ(tick.sample.tick(), k);
    EXPECT_TRUE(tick.sample.lockstep());
    EXPECT_EQ(tick.sample.step_ns(), 1'000'000);
    EXPECT_EQ(state.sample.header().seq(), k);
    EXPECT_DOUBLE_EQ(sample.sample.encoder_position()[0], q);
    EXPECT_DOUBLE_EQ(state.sample.q()[0], q);
    command.tick(k);
    commands.publish(command);
    v += 2.0 * kDt;
    q += v * kDt;
  }
  ASSERT_TRUE(sensors.wait_newer(sample, sample.count, 10s));
  EXPECT_EQ(sample.sample.header().seq(), 50u);
  EXPECT_DOUBLE_EQ(sample.sample.encoder_position()[0], q);
  runner.shutdown();
  EXPECT_EQ(runner.component().report().counter("lockstep_timeouts").value(), 0u);
}

TEST(SimRobotEngines, WithoutLockstepNorRealTimeItRunsFreeToItsDuration) {
  wbi::dds::Participant participant("engines_free");
  wbi::runtime::SystemClock clock;
  Seen seen;
  const auto registry = registry_with_toy(seen);
  wbi::runtime::ComponentRunner runner(registry.create("sim_robot"),
                                       {"sim", "sim_robot", &participant, &clock});
  runner.configure(wbi::runtime::Parameters::from_string(
      "{robot: toy_free, engine: toy, config: toy.cfg, real_time: false, duration_s: 0.5}"));
  wbi::dds::Subscriber<wbi::msg::SimulationClock> sim_clock(participant, topics::kClock,
                                                            qos::kStream);
  ASSERT_TRUE(sim_clock.wait_for_publishers(1, 10s));
  runner.activate();
  // No controller answers and nothing paces it: 500 ticks, then it stops at 0.5 s.
  wbi::dds::Received<wbi::msg::SimulationClock> tick;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (std::chrono::steady_clock::now() < deadline &&
         !(sim_clock.wait_newer(tick, tick.count, 1s) && tick.sample.tick() == 499)) {
  }
  EXPECT_EQ(tick.sample.tick(), 499u);
  EXPECT_EQ(tick.sample.time_ns(), 499'000'000);
  EXPECT_FALSE(tick.sample.lockstep());
  runner.deactivate();  // joins the loop: it ended at duration_s
  EXPECT_EQ(seen.engine->steps(), 500);
  runner.shutdown();
}

}  // namespace
