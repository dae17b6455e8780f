// The parts of wbi::recording that need no DDS: the recorder's queue (order,
// counted drops, no allocation once warm), the source stamp read from CDR
// bytes, and the QoS profile chosen from channel metadata.
#include <gtest/gtest.h>

#include <pthread.h>
#include <sched.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/msg/idl_text.hpp>

#include "allocation_counter.hpp"
#include "channel_qos.hpp"
#include "realtime_scope.hpp"
#include "record_play_support.hpp"
#include "sample_queue.hpp"
#include "source_stamp.hpp"

namespace {

using wbi::recording::SampleQueue;

std::vector<std::uint8_t> bytes_of(std::uint8_t value, std::size_t size) {
  return std::vector<std::uint8_t>(size, value);
}

int thread_policy(int* priority = nullptr) {
  int policy = -1;
  sched_param param{};
  pthread_getschedparam(pthread_self(), &policy, &param);
  if (priority != nullptr) {
    *priority = param.sched_priority;
  }
  return policy;
}

// The player's real-time scheduling: SCHED_FIFO inside the scope where the OS
// allows it (CI runs as root), the old policy after it; a reason otherwise.
TEST(RealtimeScope, RunsTheThreadFifoForItsLifeOrSaysWhyNot) {
  const int before = thread_policy();
  {
    const wbi::recording::RealtimeScope scope(7);
    int priority = 0;
    if (scope.active()) {
      EXPECT_EQ(thread_policy(&priority), SCHED_FIFO);
      EXPECT_EQ(priority, 7);
      EXPECT_EQ(scope.refusal(), "");
    } else {
      EXPECT_EQ(thread_policy(), before);
      EXPECT_NE(scope.refusal().find("SCHED_FIFO 7"), std::string::npos) << scope.refusal();
    }
  }
  EXPECT_EQ(thread_policy(), before);
  const wbi::recording::RealtimeScope off(0);
  EXPECT_FALSE(off.active());
  EXPECT_EQ(off.refusal(), "");
  EXPECT_THROW(wbi::recording::RealtimeScope(100), std::invalid_argument);
  EXPECT_THROW(wbi::recording::RealtimeScope(-1), std::invalid_argument);
}

TEST(SampleQueue, DeliversInOrderAndCountsDropsWhenFull) {
  SampleQueue queue(4);
  for (std::uint8_t i = 0; i < 6; ++i) {
    queue.push(i, 100 + i, 200 + i, bytes_of(i, 10 + i));
  }
  EXPECT_EQ(queue.dropped(), 2u);
  EXPECT_EQ(queue.high_water(), 4u);
  std::vector<std::uint32_t> sources;
  queue.drain(
      [&](const wbi::recording::QueuedSample& sample) {
        sources.push_back(sample.source);
        EXPECT_EQ(sample.log_time, 100 + sample.source);
        EXPECT_EQ(sample.publish_time, 200 + sample.source);
        EXPECT_EQ(sample.bytes,
                  bytes_of(static_cast<std::uint8_t>(sample.source), 10 + sample.source));
      },
      std::chrono::milliseconds(0));
  EXPECT_EQ(sources, (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_TRUE(queue.push(9, 0, 0, bytes_of(9, 3))) << "room again after the drain";
}

TEST(SampleQueue, AllocatesNothingOnceEverySlotHasGrown) {
  SampleQueue queue(8);
  const auto payload = bytes_of(7, 900);
  std::size_t consumed = 0;
  auto consume = [&](const wbi::recording::QueuedSample&) { ++consumed; };
  for (int i = 0; i < 8; ++i) {  // warm-up: each slot's buffer grows once
    queue.push(0, 0, 0, payload);
  }
  queue.drain(consume, std::chrono::milliseconds(0));
  const long before = wbi::test::allocation_count();
  for (int round = 0; round < 100; ++round) {
    for (int i = 0; i < 5; ++i) {
      queue.push(1, 2, 3, payload);
    }
    queue.drain(consume, std::chrono::milliseconds(0));
  }
  EXPECT_EQ(wbi::test::allocation_count() - before, 0);
  EXPECT_EQ(consumed, 8u + 500u);
}

TEST(SampleQueue, RejectsZeroCapacity) { EXPECT_THROW(SampleQueue(0), std::invalid_argument); }

TEST(SourceStamp, KnowsWhichWbiTypesStartWithAHeader) {
  for (const std::string type :
       {"SensorSample", "GroundTruth", "ActuatorCommand", "ControlParameters", "StateEstimate",
        "EstimatorParameter", "RobotDescription", "ComponentStatus"}) {
    const std::string name = "wbi::msg::" + type;
    EXPECT_TRUE(wbi::recording::starts_with_header(name, wbi::msg::idl_text_for(name))) << name;
  }
  for (const std::string type : {"SimulationClock", "ModelRequest", "ModelReply"}) {
    const std::string name = "wbi::msg::" + type;
    EXPECT_FALSE(wbi::recording::starts_with_header(name, wbi::msg::idl_text_for(name))) << name;
  }
  EXPECT_TRUE(wbi::recording::starts_with_header(
      "x::A", "struct B; /* c */ struct A // d\n { // e\n Header header; };"));
  EXPECT_FALSE(wbi::recording::starts_with_header("x::A", "struct AB { Header header; };"));
}

TEST(SourceStamp, ReadsHeaderStampFromCdrAndRefusesWhatItCannotRead) {
  for (const std::string robot : {"a", "abc", "robot_with_a_longer_name"}) {
    for (const std::uint64_t seq : {0u, 7u, 123456u}) {
      const auto cdr = wbi::test::pattern_cdr(robot, seq);
      EXPECT_EQ(wbi::recording::header_stamp_ns(cdr),
                std::optional<std::int64_t>(static_cast<std::int64_t>(seq) * 1'000'000))
          << robot << " " << seq;
    }
  }
  auto cdr = wbi::test::pattern_cdr("abc", 5);
  EXPECT_EQ(wbi::recording::header_stamp_ns(std::span(cdr).first(12)), std::nullopt)
      << "cut before the stamp";
  cdr[1] = 0x02;  // parameter-list CDR: no fixed layout
  EXPECT_EQ(wbi::recording::header_stamp_ns(cdr), std::nullopt);
  // Big-endian XCDR1 and little-endian XCDR2 (int64 aligned to 4), by hand.
  // encapsulation | name length 2 | "r\0" | 2 padding bytes | stamp 0x0102
  const std::vector<std::uint8_t> big{0x00, 0x00, 0, 0, 0, 0, 0, 2, 'r', 0,
                                      0,    0,    0, 0, 0, 0, 0, 0, 1,   2};
  EXPECT_EQ(wbi::recording::header_stamp_ns(big), std::optional<std::int64_t>(0x0102));
  const std::vector<std::uint8_t> xcdr2{0x00, 0x07, 0, 0, 2, 0, 0, 0, 'r', 0,
                                        0,    0,    3, 0, 0, 0, 0, 0, 0,   0};
  EXPECT_EQ(wbi::recording::header_stamp_ns(xcdr2), std::optional<std::int64_t>(3));
}

TEST(ChannelQos, MetadataRoundTripsToTheWriterProfile) {
  wbi::dds::TopicInfo topic;
  topic.writers = 1;
  for (const auto& [reliable, transient_local, profile] :
       {std::tuple{true, true, "wbi.stream"}, std::tuple{true, false, "wbi.command"},
        std::tuple{false, false, "wbi.status"}}) {
    topic.writers_reliable = reliable;
    topic.writers_transient_local = transient_local;
    auto metadata = wbi::recording::channel_metadata(topic);
    EXPECT_EQ(metadata.at("reliability"), reliable ? "reliable" : "best_effort");
    EXPECT_EQ(metadata.at("durability"), transient_local ? "transient_local" : "volatile");
    EXPECT_EQ(std::string(wbi::recording::profile_for(metadata)), profile);
    metadata.erase("qos_profile");  // a file from another recorder: by reliability and durability
    EXPECT_EQ(std::string(wbi::recording::profile_for(metadata)), profile);
  }
  EXPECT_EQ(std::string(wbi::recording::profile_for({})), "wbi.stream");
  EXPECT_EQ(std::string(wbi::recording::profile_for({{"qos_profile", "wbi.request_reply"}})),
            "wbi.request_reply");
}

}  // namespace
