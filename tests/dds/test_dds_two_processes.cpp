// A sensor sample crosses between two real processes on loopback: the talker
// process publishes pattern samples, this process checks every one. And a QoS
// file (WBI_QOS_FILE, a deploy file's qos_file) overrides only the profiles it
// names: seen from here, on the talker's writers.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>

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
