// The typed DDS layer between two participants of one process: samples arrive
// intact and in order, latched samples reach late joiners, the latest sample
// carries its stamps, bad settings are refused with a clear error, and a
// writer whose QoS cannot serve a reader is reported.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

#include <unistd.h>

#include <wbi/dds/domain_id.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "sample_pattern.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::dds::Participant;
using wbi::dds::Publisher;
using wbi::dds::Subscriber;
namespace qos = wbi::dds::qos;
namespace topics = wbi::dds::topics;

TEST(DdsPubSub, ReliableSamplesArriveIntactAndInOrder) {
  Participant a("a");
  Participant b("b");
  Publisher<wbi::msg::SensorSample> publisher(a, topics::sensors("robot"), qos::kCommand);
  std::vector<std::uint64_t> seen;
  std::string first_mismatch;
  Subscriber<wbi::msg::SensorSample> subscriber(
      b, topics::sensors("robot"), qos::kCommand,
      [&](const wbi::msg::SensorSample& sample, const wbi::dds::detail::SampleInfo&) {
        seen.push_back(sample.header().seq());
        if (first_mismatch.empty()) {
          first_mismatch = wbi::test::pattern_mismatch(sample, "robot");
        }
      });
  ASSERT_TRUE(publisher.wait_for_subscribers(1, 10s));
  ASSERT_TRUE(subscriber.wait_for_publishers(1, 10s));

  constexpr std::uint64_t kCount = 50;
  wbi::msg::SensorSample sample;
  for (std::uint64_t seq = 0; seq < kCount; ++seq) {
    wbi::test::fill_pattern(sample, "robot", seq);
    ASSERT_TRUE(publisher.publish(sample));
    ASSERT_TRUE(publisher.wait_acknowledged(5s));
  }
  wbi::dds::Received<wbi::msg::SensorSample> last;
  ASSERT_TRUE(subscriber.wait_newer(last, kCount - 1, 5s));
  EXPECT_EQ(last.sample.header().seq(), kCount - 1);
  EXPECT_EQ(first_mismatch, "");
  ASSERT_EQ(seen.size(), kCount);
  for (std::uint64_t i = 0; i < kCount; ++i) {
    EXPECT_EQ(seen[i], i);
  }
}

TEST(DdsPubSub, LatestCarriesStampsAndAge) {
  Participant a("a");
  Participant b("b");
  Publisher<wbi::msg::SensorSample> publisher(a, topics::sensors("stamped"), qos::kCommand);
  Subscriber<wbi::msg::SensorSample> subscriber(b, topics::sensors("stamped"), qos::kCommand);
  EXPECT_FALSE(subscriber.latest().has_value());
  ASSERT_TRUE(publisher.wait_for_subscribers(1, 10s));
  wbi::msg::SensorSample sample;
  wbi::test::fill_pattern(sample, "stamped", 7);
  const auto before = wbi::dds::detail::steady_now_ns();
  ASSERT_TRUE(publisher.publish(sample));
  wbi::dds::Received<wbi::msg::SensorSample> got;
  ASSERT_TRUE(subscriber.wait_newer(got, 0, 5s));
  EXPECT_EQ(got.sample.header().seq(), 7u);
  EXPECT_EQ(got.count, 1u);
  EXPECT_GE(got.received_ns, before);
  EXPECT_GT(got.source_stamp_ns, 0);
  EXPECT_GE(got.age_s(), 0.0);
  EXPECT_LT(got.age_s(), 60.0);
}

// read_newer / read_latest hand the newest sample over in place: no copy of
// it is made, and `read` sees it whole, with its count.
TEST(DdsPubSub, ReadHandsTheNewestSampleOverInPlace) {
  Participant a("a");
  Participant b("b");
  Publisher<wbi::msg::SensorSample> publisher(a, topics::sensors("in_place"), qos::kCommand);
  Subscriber<wbi::msg::SensorSample> subscriber(b, topics::sensors("in_place"), qos::kCommand);
  int calls = 0;
  const auto count = [&](const wbi::dds::Received<wbi::msg::SensorSample>&) { ++calls; };
  EXPECT_FALSE(subscriber.read_latest(count));
  EXPECT_FALSE(subscriber.read_newer(0, 50ms, count));
  EXPECT_EQ(calls, 0);
  ASSERT_TRUE(publisher.wait_for_subscribers(1, 10s));
  wbi::msg::SensorSample sample;
  for (std::uint64_t seq = 3; seq <= 4; ++seq) {
    wbi::test::fill_pattern(sample, "in_place", seq);
    ASSERT_TRUE(publisher.publish(sample));
  }
  std::uint64_t seq = 0;
  std::string mismatch = "not read";
  const wbi::msg::SensorSample* first_address = nullptr;
  ASSERT_TRUE(subscriber.read_newer(1, 5s, [&](const auto& received) {
    EXPECT_EQ(received.count, 2u);
    seq = received.sample.header().seq();
    mismatch = wbi::test::pattern_mismatch(received.sample, "in_place");
    first_address = &received.sample;
  }));
  EXPECT_EQ(seq, 4u);
  EXPECT_EQ(mismatch, "");
  ASSERT_TRUE(subscriber.read_latest([&](const auto& received) {
    EXPECT_EQ(&received.sample, first_address);  // the subscriber's own, not a copy
  }));
  EXPECT_FALSE(subscriber.read_newer(2, 100ms, count));  // nothing newer than the second
  EXPECT_EQ(calls, 0);
}

TEST(DdsPubSub, LatchedDescriptionReachesLateJoiner) {
  Participant a("a");
  Publisher<wbi::msg::RobotDescription> publisher(a, topics::description("late"), qos::kLatched);
  wbi::msg::RobotDescription description;
  description.header().robot("late");
  description.joint_names({"j0", "j1", "j2"});
  ASSERT_TRUE(publisher.publish(description));

  Participant b("b");  // joins after the sample was written
  Subscriber<wbi::msg::RobotDescription> subscriber(b, topics::description("late"), qos::kLatched);
  wbi::dds::Received<wbi::msg::RobotDescription> got;
  ASSERT_TRUE(subscriber.wait_newer(got, 0, 10s));
  ASSERT_EQ(got.sample.joint_names().size(), 3u);
  EXPECT_EQ(got.sample.joint_names()[2], "j2");
}

TEST(DdsPubSub, WaitTimesOutWithoutPublisher) {
  Participant a("a");
  Subscriber<wbi::msg::StateEstimate> subscriber(a, topics::state("nobody"), qos::kStream);
  wbi::dds::Received<wbi::msg::StateEstimate> got;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(subscriber.wait_newer(got, 0, 200ms));
  EXPECT_GE(std::chrono::steady_clock::now() - start, 200ms);
}

// A command must reach the robot, not only someone: the estimator reads the
// commands too, so "a reader matched" can be true while the robot's reader
// is not yet, and a command written then never reaches the robot.
TEST(DdsPubSub, WaitsForTheReaderOfOneParticipant) {
  Participant controller("controller");
  Participant robot("robot");
  Participant estimator("estimator");
  Publisher<wbi::msg::ActuatorCommand> commands(controller, topics::commands("arm"), qos::kCommand);
  Publisher<wbi::msg::RobotDescription> description(robot, topics::description("arm"),
                                                    qos::kLatched);
  Subscriber<wbi::msg::ActuatorCommand> estimator_reads(estimator, topics::commands("arm"),
                                                        qos::kCommand);
  ASSERT_TRUE(commands.wait_for_subscribers(1, 10s));
  // The estimator's reader is matched; the robot has none yet.
  EXPECT_FALSE(commands.wait_for_subscriber_of(description.guid(), 200ms));
  EXPECT_TRUE(commands.wait_for_subscriber_of(estimator_reads.guid(), 0s));
  Subscriber<wbi::msg::ActuatorCommand> robot_reads(robot, topics::commands("arm"), qos::kCommand);
  EXPECT_TRUE(commands.wait_for_subscriber_of(description.guid(), 10s));
}

TEST(DdsPubSub, SampleBeyondItsBoundIsNotPublished) {
  Participant a("a");
  Publisher<wbi::msg::SensorSample> publisher(a, topics::sensors("bounded"), qos::kStream);
  wbi::msg::SensorSample sample;
  const std::vector<double> too_many(wbi::msg::MAX_JOINTS * 4, 1.0);
  sample.encoder_position(too_many);
  sample.joint_torque(too_many);
  sample.motor_pwm(too_many);
  EXPECT_FALSE(publisher.publish(sample));
  sample.encoder_position(std::vector<double>(wbi::msg::MAX_JOINTS, 1.0));
  sample.joint_torque({});
  sample.motor_pwm({});
  EXPECT_TRUE(publisher.publish(sample));
}

TEST(DdsPubSub, UnknownQosProfileIsNamed) {
  Participant a("a");
  try {
    Publisher<wbi::msg::SensorSample> publisher(a, topics::sensors("x"), "wbi.no_such_profile");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("wbi.no_such_profile"), std::string::npos) << e.what();
  }
}

TEST(DdsPubSub, BestEffortWriterAndReliableReaderAreReported) {
  // As a process started without a real-time deploy's qos_file would see its
  // best-effort streams: no match, and the subscriber says why.
  Participant a("a");
  Participant b("b");
  Publisher<wbi::msg::SensorSample> best_effort(a, topics::sensors("incompatible"), qos::kStatus);
  testing::internal::CaptureStderr();
  {
    Subscriber<wbi::msg::SensorSample> reliable(b, topics::sensors("incompatible"), qos::kStream);
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (reliable.incompatible_writers() == 0 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(10ms);  // discovery has no event to wait on here
    }
    // At least once: Fast DDS may report the one writer again (2 in a CI run).
    EXPECT_GE(reliable.incompatible_writers(), 1);
    EXPECT_EQ(reliable.matched(), 0);
  }
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("a writer of 'wbi/incompatible/sensors' does not match this reader: "
                      "incompatible reliability QoS"),
            std::string::npos)
      << said;
}

TEST(DdsPubSub, TopicWithAnotherTypeIsRefused) {
  Participant a("a");
  Publisher<wbi::msg::SensorSample> sensors(a, "wbi/typed/topic", qos::kStream);
  EXPECT_THROW(Publisher<wbi::msg::StateEstimate>(a, "wbi/typed/topic", qos::kStream),
               std::invalid_argument);
}

TEST(DdsPubSub, BadDomainIdIsRefused) {
  wbi::dds::ParticipantOptions options;
  options.domain_id = 500;
  EXPECT_THROW(Participant{options}, std::invalid_argument);
  const char* saved = std::getenv("WBI_DOMAIN_ID");
  const std::string restore = saved != nullptr ? saved : "";
  setenv("WBI_DOMAIN_ID", "seven", 1);
  EXPECT_THROW(wbi::dds::domain_id_from_environment(), std::invalid_argument);
  setenv("WBI_DOMAIN_ID", restore.c_str(), 1);
}

// The highest domain id accepted is one Fast DDS can open: on 232 it ended the
// process while creating the participant (its ports past 65535), after wbi had
// accepted the id. Created here with the default (localhost) discovery; no
// test takes 231 as its own domain (they count up from 1).
TEST(DdsPubSub, TheHighestDomainIdOpensAndTheNextIsRefused) {
  wbi::dds::ParticipantOptions options;
  options.domain_id = wbi::dds::kMaxDomainId;
  Participant highest(options);
  options.domain_id = wbi::dds::kMaxDomainId + 1;
  try {
    Participant{options};
    ADD_FAILURE() << "domain " << options.domain_id << " was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "DDS domain id must be in [0, 231], got 232");
  }
}

}  // namespace

namespace {

// Discovery names a topic's publishers by participant: name, host, process id
// (what a robot that finds its name taken prints).
TEST(DdsDiscovery, PublishersAreNamedByParticipantHostAndProcess) {
  Participant a("observer");
  Participant b("publisher_b");
  Publisher<wbi::msg::RobotDescription> writer(b, topics::description("named"), qos::kLatched);
  std::vector<wbi::dds::ParticipantInfo> publishers;
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while ((publishers.empty() || publishers.front().name.empty()) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);  // polling discovery: no event to wait on here
    publishers = a.publishers_of(topics::description("named"));
  }
  ASSERT_EQ(publishers.size(), 1u);
  EXPECT_EQ(publishers.front().name, "publisher_b");
  EXPECT_EQ(publishers.front().guid_prefix, b.info().guid_prefix);
  EXPECT_EQ(publishers.front().pid, static_cast<long>(getpid()));
  EXPECT_EQ(publishers.front().host, a.info().host);
  EXPECT_EQ(publishers.front().start_ns, b.info().start_ns);
  EXPECT_FALSE(a.info().host.empty());
  EXPECT_NE(a.info().guid_prefix, b.info().guid_prefix);
  EXPECT_TRUE(a.publishers_of(topics::description("nobody")).empty());
}

}  // namespace
