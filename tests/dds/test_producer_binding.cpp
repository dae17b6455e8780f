// One producer per stream (wbi/dds/producers.hpp), between real participants
// of one process: a bound reader takes the first writer's samples and drops a
// second writer's, counted and said once naming it; when the bound writer's
// participant leaves, a new writer is taken, the second one still not; with
// an owner, a writer of another participant taken before the owner was heard
// is dropped once it is, and once the owner's participant has left, the first
// sample of a restarted robot that comes before its description is taken.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::dds::Participant;
using wbi::dds::ProducerEvent;
using wbi::dds::ProducerPolicy;
using wbi::dds::Publisher;
using wbi::dds::Subscriber;
using Sample = wbi::msg::SensorSample;
namespace qos = wbi::dds::qos;
namespace topics = wbi::dds::topics;

// What a bound reader took (the header's robot field names the sender) and was told.
struct Seen {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::string> taken;
  std::vector<std::string> lines;  // events with a text
  std::size_t foreign_events = 0;

  void take(const Sample& sample) {
    std::lock_guard lock(mutex);
    taken.push_back(sample.header().robot().to_string());
    changed.notify_all();
  }
  void hear(const ProducerEvent& event) {
    std::lock_guard lock(mutex);
    if (event.kind == ProducerEvent::Kind::foreign_sample) {
      ++foreign_events;
    }
    if (!event.text.empty()) {
      lines.emplace_back(event.text);
    }
    changed.notify_all();
  }
  template <class Condition>
  bool wait(Condition condition) {
    std::unique_lock lock(mutex);
    return changed.wait_for(lock, 10s, [&] { return condition(*this); });
  }
  std::size_t count(const std::string& sender) const {
    return static_cast<std::size_t>(std::count(taken.begin(), taken.end(), sender));
  }
};

void send(Publisher<Sample>& publisher, const std::string& sender, std::uint64_t seq) {
  Sample sample;
  sample.header().robot(sender);
  sample.header().seq(seq);
  publisher.publish(sample);
}

// Publishes until `done` holds (a best-effort-free reliable stream still needs
// the reader matched: samples written before are not awaited).
template <class Done>
bool send_until(Publisher<Sample>& publisher, const std::string& sender, Seen& seen, Done done) {
  for (std::uint64_t seq = 0; seq < 500; ++seq) {
    send(publisher, sender, seq);
    std::unique_lock lock(seen.mutex);
    if (seen.changed.wait_for(lock, 20ms, [&] { return done(seen); })) {
      return true;
    }
  }
  return false;
}

const std::string kTopic = topics::sensors("bound");

using Description = Subscriber<wbi::msg::RobotDescription>;

// A reader of a robot's description and one of its sensors owned by it, as the
// estimator and the proxy read them; `owner(description)` makes the owner.
struct OwnedSensors {
  template <class MakeOwner>
  OwnedSensors(Participant& participant, Seen& seen, MakeOwner make_owner)
      : description(participant, topics::description("bound"), qos::kLatched, nullptr,
                    ProducerPolicy::one()),
        sensors(
            participant, kTopic, qos::kCommand,
            [&seen](const Sample& sample, const wbi::dds::detail::SampleInfo&) {
              seen.take(sample);
            },
            ProducerPolicy::owned_by(make_owner(description),
                                     [&seen](const ProducerEvent& event) { seen.hear(event); })) {}
  Description description;
  Subscriber<Sample> sensors;
};

TEST(ProducerBinding, TheFirstWriterIsTakenAndASecondIsDroppedCountedAndNamedOnce) {
  Participant reader_side("reader");
  Participant robot("robot");
  Participant rogue("rogue");
  Seen seen;
  Subscriber<Sample> subscriber(
      reader_side, kTopic, qos::kCommand,
      [&](const Sample& sample, const wbi::dds::detail::SampleInfo&) { seen.take(sample); },
      ProducerPolicy::one([&](const ProducerEvent& event) { seen.hear(event); }));
  Publisher<Sample> robot_writer(robot, kTopic, qos::kCommand);
  ASSERT_TRUE(send_until(robot_writer, "robot", seen, [](Seen& s) { return s.count("robot"); }));

  Publisher<Sample> rogue_writer(rogue, kTopic, qos::kCommand);
  ASSERT_TRUE(
      send_until(rogue_writer, "rogue", seen, [](Seen& s) { return s.foreign_events >= 5; }));
  ASSERT_TRUE(
      send_until(robot_writer, "robot", seen, [](Seen& s) { return s.count("robot") >= 3; }));

  std::lock_guard lock(seen.mutex);
  EXPECT_EQ(seen.count("rogue"), 0u) << "a second writer's sample was taken";
  ASSERT_EQ(seen.lines.size(), 1u) << "said once per foreign writer, not per sample";
  EXPECT_NE(seen.lines[0].find("participant 'rogue'"), std::string::npos) << seen.lines[0];
  EXPECT_NE(seen.lines[0].find("participant 'robot'"), std::string::npos) << seen.lines[0];
  const auto counts = subscriber.producers();
  EXPECT_EQ(counts.foreign_writers, 1u);
  EXPECT_EQ(counts.foreign_samples, seen.foreign_events);
  EXPECT_EQ(counts.rebinds, 0u);
  EXPECT_EQ(counts.bound, robot_writer.guid());
}

TEST(ProducerBinding, WhenTheBoundWriterLeavesANewOneIsTakenNotTheSecond) {
  Participant reader_side("reader");
  Participant rogue("rogue");
  Seen seen;
  Subscriber<Sample> subscriber(
      reader_side, kTopic, qos::kCommand,
      [&](const Sample& sample, const wbi::dds::detail::SampleInfo&) { seen.take(sample); },
      ProducerPolicy::one([&](const ProducerEvent& event) { seen.hear(event); }));
  Publisher<Sample> rogue_writer(rogue, kTopic, qos::kCommand);
  {
    Participant first("robot");
    Publisher<Sample> first_writer(first, kTopic, qos::kCommand);
    // The rogue must not be heard first: its reader is matched only after the robot's sample.
    ASSERT_TRUE(rogue_writer.wait_for_subscribers(1, 10s));
    ASSERT_TRUE(send_until(first_writer, "robot", seen, [](Seen& s) { return s.count("robot"); }));
    ASSERT_TRUE(
        send_until(rogue_writer, "rogue", seen, [](Seen& s) { return s.foreign_events >= 1; }));
    // Both publishing: the rogue is a second producer, not a successor.
    ASSERT_TRUE(
        send_until(first_writer, "robot", seen, [](Seen& s) { return s.count("robot") >= 2; }));
  }  // the robot's participant leaves: DDS unmatches its writer
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (subscriber.matched() != 1 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(
        10ms);  // polling the match count: the subscriber has no event for it
  }
  ASSERT_EQ(subscriber.matched(), 1) << "the robot's writer was not unmatched";

  Participant second("robot_again");
  Publisher<Sample> second_writer(second, kTopic, qos::kCommand);
  // The rogue keeps publishing meanwhile: it was a second producer, not the successor.
  send(rogue_writer, "rogue", 1000);
  ASSERT_TRUE(
      send_until(second_writer, "again", seen, [](Seen& s) { return s.count("again") >= 2; }));
  send(rogue_writer, "rogue", 1001);
  ASSERT_TRUE(seen.wait([](Seen& s) { return s.foreign_events >= 3; }));

  std::lock_guard lock(seen.mutex);
  EXPECT_EQ(seen.count("rogue"), 0u);
  const auto counts = subscriber.producers();
  EXPECT_EQ(counts.rebinds, 1u);
  EXPECT_EQ(counts.bound, second_writer.guid());
  ASSERT_EQ(seen.lines.size(), 2u);  // the rogue once, the rebind once
  EXPECT_NE(seen.lines[1].find("now taking the samples of participant 'robot_again'"),
            std::string::npos)
      << seen.lines[1];
}

TEST(ProducerBinding, AStreamOwnedByTheDescriptionDropsAWriterTakenBeforeTheOwnerWasHeard) {
  Participant reader_side("reader");
  Participant rogue("rogue");
  Participant robot("robot");
  Seen seen;
  OwnedSensors owned(reader_side, seen, [](const Description& description) {
    return [&description] { return description.producers().bound; };
  });
  auto& description = owned.description;
  auto& sensors = owned.sensors;

  // The rogue publishes before any description: taken, provisionally.
  Publisher<Sample> rogue_writer(rogue, kTopic, qos::kCommand);
  ASSERT_TRUE(send_until(rogue_writer, "rogue", seen, [](Seen& s) { return s.count("rogue"); }));

  Publisher<wbi::msg::RobotDescription> robot_description(robot, topics::description("bound"),
                                                          qos::kLatched);
  wbi::msg::RobotDescription latched;
  latched.header().robot("bound");
  robot_description.publish(latched);
  wbi::dds::Received<wbi::msg::RobotDescription> heard;
  ASSERT_TRUE(description.wait_newer(heard, 0, 10s));
  const std::size_t rogue_taken = [&] {
    std::lock_guard lock(seen.mutex);
    return seen.count("rogue");
  }();

  Publisher<Sample> robot_sensors(robot, kTopic, qos::kCommand);
  ASSERT_TRUE(send_until(robot_sensors, "robot", seen, [](Seen& s) { return s.count("robot"); }));
  ASSERT_TRUE(
      send_until(rogue_writer, "rogue", seen, [](Seen& s) { return s.foreign_events >= 3; }));

  std::lock_guard lock(seen.mutex);
  EXPECT_EQ(seen.count("rogue"), rogue_taken) << "the rogue was taken once the owner was known";
  EXPECT_EQ(sensors.producers().bound, robot_sensors.guid());
  ASSERT_FALSE(seen.lines.empty());
  EXPECT_NE(seen.lines.back().find("participant 'rogue'"), std::string::npos) << seen.lines.back();
}

// The fault that found it (test_fault_balance_robot, lockstep): the robot is
// stopped and started again; the estimator heard the new robot's first sensor
// sample before its description, dropped it as a second writer's, and the
// lockstep robot, waiting for a command computed from that sample, never stepped.
TEST(ProducerBinding, ARestartedOwnersFirstSampleBeforeItsDescriptionIsTaken) {
  Participant reader_side("reader");
  Seen seen;
  OwnedSensors owned(reader_side, seen, [&](const Description& description) {
    return wbi::dds::description_owner(reader_side, description);
  });
  auto& description = owned.description;
  auto& sensors = owned.sensors;
  wbi::msg::RobotDescription latched;
  latched.header().robot("bound");
  wbi::dds::Received<wbi::msg::RobotDescription> heard;
  wbi::dds::detail::Guid first_description{};
  {
    Participant first("robot");
    Publisher<wbi::msg::RobotDescription> first_writer(first, topics::description("bound"),
                                                       qos::kLatched);
    first_description = first_writer.guid();
    first_writer.publish(latched);
    ASSERT_TRUE(description.wait_newer(heard, 0, 10s));
    Publisher<Sample> first_sensors(first, kTopic, qos::kCommand);
    ASSERT_TRUE(send_until(first_sensors, "robot", seen, [](Seen& s) { return s.count("robot"); }));
  }  // the robot stops: its participant leaves discovery
  ASSERT_TRUE(
      wbi::test::eventually([&] { return reader_side.participant_gone(first_description); }, 10s))
      << "the stopped robot's participant is still in discovery";

  // The restarted robot's sensors before its description: its first sample heard is taken.
  Participant second("robot_again");
  Publisher<Sample> second_sensors(second, kTopic, qos::kCommand);
  ASSERT_TRUE(second_sensors.wait_for_subscribers(1, 10s));
  send(second_sensors, "again", 0);
  ASSERT_TRUE(seen.wait([](Seen& s) { return s.count("again") == 1; }))
      << "the restarted robot's first sample was dropped";
  // A rogue now is not taken; the robot's description then moves the owner.
  Participant rogue("rogue");
  Publisher<Sample> rogue_writer(rogue, kTopic, qos::kCommand);
  ASSERT_TRUE(
      send_until(rogue_writer, "rogue", seen, [](Seen& s) { return s.foreign_events >= 1; }));
  Publisher<wbi::msg::RobotDescription> second_description(second, topics::description("bound"),
                                                           qos::kLatched);
  second_description.publish(latched);
  ASSERT_TRUE(wbi::test::eventually(
      [&] { return description.producers().bound == second_description.guid(); }, 10s));
  ASSERT_TRUE(
      send_until(second_sensors, "again", seen, [](Seen& s) { return s.count("again") >= 2; }));
  const std::size_t rogue_events = [&] {
    std::lock_guard lock(seen.mutex);
    return seen.foreign_events;
  }();
  send(rogue_writer, "rogue", 1000);
  ASSERT_TRUE(seen.wait([&](Seen& s) { return s.foreign_events > rogue_events; }));

  std::lock_guard lock(seen.mutex);
  EXPECT_EQ(seen.count("rogue"), 0u);
  EXPECT_EQ(sensors.producers().bound, second_sensors.guid());
  const auto said = [&](const std::string& text) {
    return std::any_of(seen.lines.begin(), seen.lines.end(), [&](const std::string& line) {
      return line.find(text) != std::string::npos;
    });
  };
  EXPECT_TRUE(said("now taking the samples of participant 'robot_again'"));
  EXPECT_FALSE(said("dropping the samples of a second writer, participant 'robot_again'"))
      << "a sample of the restarted robot was dropped";
  EXPECT_TRUE(said("dropping the samples of a second writer, participant 'rogue'"));
}

}  // namespace
