// The robot loop allocates nothing per tick once running: the toy engine
// (toy_engine.hpp) notes the heap allocations of the driver's loop thread at
// each step(), while the test answers every tick in lockstep. A tick is the
// whole loop: read, sensor sample, ground truth and clock published, lockstep
// wait, joint control, write, step.
#include <gtest/gtest.h>

#include <chrono>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/runtime/runner.hpp>

#include "allocation_counter.hpp"
#include "toy_engine.hpp"

namespace {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;

TEST(RobotLoop, ALockstepTickAllocatesNothing) {
  constexpr std::uint64_t kTicks = 200;
  wbi::dds::Participant participant("loop_no_alloc");
  wbi::runtime::SystemClock clock;
  wbi::test::Seen seen;
  const auto registry = wbi::test::registry_with_toy(seen, &wbi::test::thread_allocation_count);
  wbi::runtime::ComponentRunner runner(registry.create("sim_robot"),
                                       {"sim", "sim_robot", &participant, &clock});
  runner.configure(wbi::runtime::Parameters::from_string(
      "{robot: toy_no_alloc, engine: toy, config: toy.cfg, lockstep: true,"
      " lockstep_controllers: [test]}"));
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(participant, topics::sensors("toy_no_alloc"),
                                                       qos::kStream);
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(
      participant, topics::commands("toy_no_alloc"), qos::kCommand);
  ASSERT_TRUE(sensors.wait_for_publishers(1, 10s));
  ASSERT_TRUE(commands.wait_for_subscribers(1, 10s));
  runner.activate();

  wbi::msg::ActuatorCommand command;
  command.controller("test");
  command.joints({0});
  command.modes({wbi::msg::VELOCITY});  // streaming: the watchdog is checked every tick
  command.references({0.1});
  wbi::dds::Received<wbi::msg::SensorSample> sample;
  for (std::uint64_t k = 0; k < kTicks; ++k) {
    ASSERT_TRUE(sensors.wait_newer(sample, sample.count, 10s)) << "tick " << k;
    ASSERT_EQ(sample.sample.header().seq(), k);
    command.tick(k);
    commands.publish(command);
  }
  ASSERT_TRUE(sensors.wait_newer(sample, sample.count, 10s));  // tick kTicks is out
  ASSERT_EQ(seen.engine->steps(), static_cast<std::int64_t>(kTicks));
  // After a few ticks to warm up (first samples, DDS history), none allocates.
  long most = 0;
  for (std::size_t k = 20; k < kTicks; ++k) {
    most = std::max(most, seen.engine->growth_in_step(k));
  }
  EXPECT_EQ(most, 0) << "heap allocations in one tick of the robot loop's thread";
  runner.shutdown();
}

}  // namespace
