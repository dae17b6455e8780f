// A sensor sample crosses between two real processes on loopback: the talker
// process publishes pattern samples, this process checks every one. And a QoS
// file (WBI_QOS_FILE, a deploy file's qos_file) overrides only the profiles it
// names: seen from here, on the talker's writers. A reader that falls behind a
// stream's writer is told how many samples it lost.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <optional>
#include <string>

#include <wbi/dds/join_options.hpp>
#include <wbi/dds/raw_subscriber.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "child_process.hpp"
#include "sample_pattern.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

TEST(DdsTwoProcesses, EverySampleArrivesIntact) {
  constexpr std::uint64_t kCount = 200;
  wbi::dds::Participant participant("listener");
  std::vector<std::uint64_t> seen;
  std::string first_mismatch;
  wbi::dds::Subscriber<wbi::msg::SensorSample> subscriber(
      participant, wbi::dds::topics::sensors("twoproc"), wbi::dds::qos::kLatched,
      [&](const wbi::msg::SensorSample& sample, const wbi::dds::detail::SampleInfo&) {
        seen.push_back(sample.header().seq());
        if (first_mismatch.empty()) {
          first_mismatch = wbi::test::pattern_mismatch(sample, "twoproc");
        }
      });
  wbi::test::ChildProcess talker(wbi::test::binary_dir() / "tests" / "wbi_test_talker",
                                 {"twoproc", std::to_string(kCount)});
  ASSERT_TRUE(subscriber.wait_for_publishers(1, 20s)) << talker.output();
  const auto code = talker.wait(60s);
  ASSERT_TRUE(code.has_value()) << "talker did not finish: " << talker.output();
  EXPECT_EQ(*code, 0) << talker.output();

  wbi::dds::Received<wbi::msg::SensorSample> last;
  ASSERT_TRUE(subscriber.wait_newer(last, kCount - 1, 5s))
      << "received " << subscriber.count() << " samples, callback saw " << seen.size()
      << (seen.empty() ? std::string()
                       : ", first seq " + std::to_string(seen.front()) + ", last " +
                             std::to_string(seen.back()));
  EXPECT_EQ(first_mismatch, "");
  ASSERT_EQ(seen.size(), kCount);
  for (std::uint64_t i = 0; i < kCount; ++i) {
    ASSERT_EQ(seen[i], i);
  }
}

// A stream's writer keeps its newest sample only: a reader whose thread is held
// while a burst arrives loses what overflows its socket's receive buffer, and
// must be told so (a recorder reports it: tools/recording/README.md).
TEST(DdsTwoProcesses, AReaderThatFallsBehindAStreamIsToldWhatItLost) {
  constexpr std::int64_t kCount = 2000;
  wbi::dds::ParticipantOptions options;
  options.name = "late reader";
  wbi::dds::apply_environment(options);
  options.udp_receive_buffer_bytes = 65536;  // a few dozen samples: the burst overflows it
  wbi::dds::Participant participant(options);
  std::atomic<std::int64_t> received{0};
  std::atomic<bool> burst_sent{false};
  const wbi::dds::TopicInfo topic{
      wbi::dds::topics::sensors("burst"), "wbi::msg::SensorSample", 1, 0, true, true};
  wbi::dds::RawSubscriber reader(participant, topic, [&](const wbi::dds::RawSample&) {
    if (received.fetch_add(1) == 1) {
      // The burst's first sample holds the receive thread until the whole
      // burst is sent: every datagram behind it waits in the socket's buffer.
      wbi::test::eventually([&] { return burst_sent.load(); }, 20s);
    }
  });
  wbi::test::ChildProcess talker(wbi::test::binary_dir() / "tests" / "wbi_test_talker",
                                 {"burst", std::to_string(kCount), "burst"});
  const bool sent = talker.wait_for_output("talker: done", 20s);
  burst_sent = true;
  ASSERT_TRUE(sent) << talker.output();
  // Every sample is received or reported lost, none goes missing in silence.
  EXPECT_TRUE(
      wbi::test::eventually([&] { return received.load() + reader.samples_lost() == kCount; }, 20s))
      << "received " << received.load() << ", reported lost " << reader.samples_lost() << " of "
      << kCount << "; " << talker.output();
  EXPECT_GT(reader.samples_lost(), 0) << "the held thread lost nothing: the buffer did not fill";
  std::cout << "burst of " << kCount << ": received " << received.load() << ", reported lost "
            << reader.samples_lost() << std::endl;
  talker.stop();
}

// The QoS of the writers of the talker started with env (e.g. WBI_QOS_FILE=...).
struct TalkerQos {
  std::optional<wbi::dds::TopicInfo> stream;
  std::optional<wbi::dds::TopicInfo> command;
  std::string output;
};
TalkerQos talker_qos(const std::string& robot, const std::vector<std::string>& env) {
  wbi::dds::Participant participant("qos_probe");
  wbi::test::ChildProcess talker(wbi::test::binary_dir() / "tests" / "wbi_test_talker",
                                 {robot, "0"}, env);
  TalkerQos qos;
  qos.stream = participant.wait_for_topic(wbi::dds::topics::sensors(robot), 20s);
  qos.command = participant.wait_for_topic(wbi::dds::topics::commands(robot), 20s);
  talker.stop();
  qos.output = talker.output();
  return qos;
}

TEST(DdsQosFile, BuiltInStreamsAreReliableAndKeepTheirLastSample) {
  const TalkerQos qos = talker_qos("qos_builtin", {});
  ASSERT_TRUE(qos.stream && qos.command) << qos.output;
  EXPECT_TRUE(qos.stream->writers_reliable);
  EXPECT_TRUE(qos.stream->writers_transient_local);
  EXPECT_TRUE(qos.command->writers_reliable);
}

TEST(DdsQosFile, TheRealTimeFileMakesStreamsBestEffortAndKeepsTheRest) {
  const auto file = wbi::test::source_dir() / "deploy" / "qos_realtime.xml";
  const TalkerQos qos = talker_qos("qos_realtime", {"WBI_QOS_FILE=" + file.string()});
  ASSERT_TRUE(qos.stream && qos.command) << qos.output;
  EXPECT_FALSE(qos.stream->writers_reliable);
  EXPECT_FALSE(qos.stream->writers_transient_local);
  EXPECT_TRUE(qos.command->writers_reliable) << "the built-in wbi.command was not filled in";
}

TEST(DdsQosFile, AMissingFileIsNamed) {
  wbi::test::ChildProcess talker(wbi::test::binary_dir() / "tests" / "wbi_test_talker",
                                 {"qos_missing", "0"}, {"WBI_QOS_FILE=/nonexistent/qos.xml"});
  const auto code = talker.wait(20s);
  ASSERT_TRUE(code.has_value()) << talker.output();
  EXPECT_NE(*code, 0);
  EXPECT_NE(talker.output().find("/nonexistent/qos.xml"), std::string::npos) << talker.output();
}

}  // namespace
