// The robot loop allocates nothing per tick once running, beyond what Fast DDS
// allocates inside its writes: the toy engine (toy_engine.hpp) notes the heap
// allocations of the driver's loop thread at each step(), while the test
// answers every tick in lockstep. A tick is the whole loop: read, sensor
// sample, ground truth and clock published, lockstep wait, joint control
// (watchdog included), write, step. The writes' own allocations are measured
// apart, on this thread, with the same three messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/runtime/runner.hpp>

#include "allocation_counter.hpp"
#include "test_support.hpp"
#include "toy_engine.hpp"

namespace {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;

// Heap allocations of one write of each message the loop publishes per tick,
// on this thread, the fewest of a few: writers of their own topics, each read
// in this process as the loop's are (a local reader's delivery runs on the
// writer's thread).
long allocations_of_the_ticks_writes(wbi::dds::Participant& participant,
                                     const wbi::msg::SensorSample& sensors,
                                     const wbi::msg::GroundTruth& truth,
                                     const wbi::msg::SimulationClock& clock) {
  const std::string robot = "toy_no_alloc_reference";
  wbi::dds::Publisher<wbi::msg::SensorSample> sensors_writer(participant, topics::sensors(robot),
                                                             qos::kStream);
  wbi::dds::Publisher<wbi::msg::GroundTruth> truth_writer(participant, topics::ground_truth(robot),
                                                          qos::kStream);
  wbi::dds::Publisher<wbi::msg::SimulationClock> clock_writer(
      participant, "wbi/" + robot + "/clock", qos::kStream);
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors_reader(participant, topics::sensors(robot),
                                                              qos::kStream);
  wbi::dds::Subscriber<wbi::msg::GroundTruth> truth_reader(participant, topics::ground_truth(robot),
                                                           qos::kStream);
  wbi::dds::Subscriber<wbi::msg::SimulationClock> clock_reader(
      participant, "wbi/" + robot + "/clock", qos::kStream);
  EXPECT_TRUE(sensors_writer.wait_for_subscribers(1, 10s) &&
              truth_writer.wait_for_subscribers(1, 10s) &&
              clock_writer.wait_for_subscribers(1, 10s));
  long fewest = -1;
  for (int k = 0; k < 40; ++k) {
    const long before = wbi::test::thread_allocation_count();
    sensors_writer.publish(sensors);
    truth_writer.publish(truth);
    clock_writer.publish(clock);
    const long made = wbi::test::thread_allocation_count() - before;
    fewest = k < 20 || fewest < 0 ? made : std::min(fewest, made);  // 20 to warm up
  }
  return fewest;
}

// extra: more sim_robot parameters, e.g. ", ground_truth_file: FILE".
void check_lockstep_ticks(const std::string& extra) {
  constexpr std::uint64_t kTicks = 200;
  wbi::dds::Participant participant("loop_no_alloc");
  wbi::runtime::SystemClock clock;
  wbi::test::Seen seen;
  const auto registry = wbi::test::registry_with_toy(seen, &wbi::test::thread_allocation_count);
  wbi::runtime::ComponentRunner runner(registry.create("sim_robot"),
                                       {"sim", "sim_robot", &participant, &clock});
  runner.configure(wbi::runtime::Parameters::from_string(
      "{robot: toy_no_alloc, engine: toy, config: toy.cfg, lockstep: true,"
      " lockstep_controllers: [test]" +
      extra + "}"));
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(participant, topics::sensors("toy_no_alloc"),
                                                       qos::kStream);
  wbi::dds::Subscriber<wbi::msg::GroundTruth> truth(
      participant, topics::ground_truth("toy_no_alloc"), qos::kStream);
  wbi::dds::Subscriber<wbi::msg::SimulationClock> sim_clock(participant, topics::kClock,
                                                            qos::kStream);
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(
      participant, topics::commands("toy_no_alloc"), qos::kCommand);
  ASSERT_TRUE(sensors.wait_for_publishers(1, 10s));
  ASSERT_TRUE(commands.wait_for_subscribers(1, 10s));
  runner.activate();

  wbi::msg::ActuatorCommand command;
  command.header().robot("toy_no_alloc");
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
  // After a few ticks to warm up (first samples, DDS history), a tick
  // allocates what its three writes allocate, and nothing else.
  const auto last_truth = truth.latest();
  const auto last_clock = sim_clock.latest();
  ASSERT_TRUE(last_truth && last_clock);
  const long writes = allocations_of_the_ticks_writes(participant, sample.sample,
                                                      last_truth->sample, last_clock->sample);
  // A per-tick allocation shows in every tick, DDS noise (acknowledgements,
  // history) in some: the fewest of a tick's allocations is the loop's own.
  long fewest = -1;
  for (std::size_t k = 20; k < kTicks; ++k) {
    const long made = seen.engine->growth_in_step(k);
    fewest = fewest < 0 ? made : std::min(fewest, made);
  }
  EXPECT_GT(writes, 0) << "the writes were measured";
  EXPECT_LE(fewest, writes) << "heap allocations in one tick of the robot loop's thread, beyond "
                            << writes << " inside its DDS writes";
  runner.shutdown();
}

TEST(RobotLoop, ALockstepTickAllocatesNothingButInsideItsDdsWrites) { check_lockstep_ticks(""); }

// The same with every tick's ground truth written to a file (ground_truth_file):
// the chunk buffer keeps its capacity, a tick's write allocates nothing.
TEST(RobotLoop, WritingTheGroundTruthToAFileAllocatesNothingPerTick) {
  const auto file = wbi::test::binary_dir() / "tests" / "loop_no_alloc_ground_truth.mcap";
  check_lockstep_ticks(", ground_truth_file: " + file.string());
  EXPECT_GT(std::filesystem::file_size(file), 0u);
  std::filesystem::remove(file);
}

}  // namespace
