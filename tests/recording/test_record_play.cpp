// `wbi record` and `wbi play` as a user runs them: real publisher processes
// (tests/dds talker), the recorder and the player as `wbi` processes, and
// subscribers in this process; loopback discovery on the test's own domain.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <wbi/dds/publisher.hpp>
#include <wbi/mcap/reader.hpp>

#include "mcap_samples.hpp"
#include "record_play_support.hpp"
#include "sensor_listener.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::uint64_t system_now_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

class RecordPlay : public ::testing::Test {
 protected:
  void TearDown() override {
    for (const auto& file : files_) {
      std::filesystem::remove(file);
    }
  }
  std::filesystem::path file(const std::string& name) {
    files_.push_back(wbi::test::scratch_file(name));
    return files_.back();
  }

 private:
  std::vector<std::filesystem::path> files_;
};

// Records two counted talkers (the second starts after the first is done, so
// its topic appears mid-recording) and ignores an excluded and an unmatched one.
TEST_F(RecordPlay, RecordsLivePublishersByteForByteWithFilters) {
  const auto out = file("live.mcap");
  ChildProcess recorder(wbi::test::wbi_program(), {"record", "-o", out.string(), "wbi/rec_.*",
                                                   "--exclude", "wbi/rec_skip/.*"});
  ASSERT_TRUE(recorder.wait_for_output("recording to", 20s)) << recorder.output();
  ChildProcess skipped(wbi::test::talker_program(), {"rec_skip", "0"});
  ChildProcess unmatched(wbi::test::talker_program(), {"other", "0"});
  {
    ChildProcess first(wbi::test::talker_program(), {"rec_a", "200"});
    ASSERT_EQ(first.wait(60s), std::optional<int>(0)) << first.output() << recorder.output();
  }
  {
    ChildProcess late(wbi::test::talker_program(), {"rec_b", "100"});
    ASSERT_EQ(late.wait(60s), std::optional<int>(0)) << late.output() << recorder.output();
  }
  ASSERT_EQ(recorder.stop(SIGINT, 20s), 0) << recorder.output();
  EXPECT_TRUE(contains(recorder.output(), "dropped 0, lost before the recorder 0"))
      << recorder.output();

  const wbi::mcap::Reader reader(out);
  std::set<std::string> topics;
  for (const auto& [id, channel] : reader.info().channels) {
    topics.insert(channel.topic);
    EXPECT_EQ(channel.message_encoding, "cdr");
    EXPECT_EQ(channel.metadata.at("reliability"), "reliable");
    EXPECT_EQ(channel.metadata.at("durability"), "transient_local");
    EXPECT_TRUE(channel.metadata.count("history_depth"));
  }
  EXPECT_EQ(topics, (std::set<std::string>{"wbi/rec_a/sensors", "wbi/rec_b/sensors"}));
  ASSERT_EQ(reader.info().schemas.size(), 1u);  // one per type
  EXPECT_EQ(reader.info().schemas.begin()->second.encoding, "omgidl");
  EXPECT_EQ(reader.info().schemas.begin()->second.name, "wbi::msg::SensorSample");

  const auto by_topic = wbi::test::messages_by_topic(out);
  for (const auto& [robot, count] : {std::pair<std::string, std::uint64_t>{"rec_a", 200},
                                     std::pair<std::string, std::uint64_t>{"rec_b", 100}}) {
    const auto& messages = by_topic.at("wbi/" + robot + "/sensors");
    ASSERT_EQ(messages.size(), count) << robot;
    for (std::uint64_t seq = 0; seq < count; ++seq) {
      ASSERT_EQ(messages[seq].data, wbi::test::pattern_cdr(robot, seq)) << robot << " " << seq;
      ASSERT_EQ(messages[seq].publish_time, seq * 1'000'000) << "publish time = Header.stamp_ns";
      ASSERT_EQ(messages[seq].sequence, seq);
    }
  }
  EXPECT_LT(by_topic.at("wbi/rec_a/sensors").back().log_time,
            by_topic.at("wbi/rec_b/sensors").front().log_time);
}

// SIGKILL mid-run: the file reads (truncated) up to within a second of the kill.
TEST_F(RecordPlay, KilledRecorderLeavesFileReadableToTheLastFlush) {
  const auto out = file("killed.mcap");
  ChildProcess talker(wbi::test::talker_program(), {"kill_me", "0"});  // 100 Hz until stopped
  ChildProcess recorder(wbi::test::wbi_program(), {"record", "-o", out.string(), "--all"});
  ASSERT_TRUE(recorder.wait_for_output("recording 2.", 30s)) << recorder.output();
  const std::uint64_t killed_at = system_now_ns();
  recorder.stop(SIGKILL);

  const wbi::mcap::Reader reader(out);
  EXPECT_TRUE(reader.info().truncated);
  const auto by_topic = wbi::test::messages_by_topic(out);
  ASSERT_EQ(by_topic.count("wbi/kill_me/sensors"), 1u);
  const auto& messages = by_topic.at("wbi/kill_me/sensors");
  ASSERT_GT(messages.size(), 50u);
  EXPECT_LT(killed_at - messages.back().log_time, 1'000'000'000u)
      << "lost more than the last second before the kill";
  for (std::size_t i = 1; i < messages.size(); ++i) {
    ASSERT_EQ(messages[i].sequence, messages[i - 1].sequence + 1) << "a gap in the recording";
  }

  // What could be read, then one line on where the file ends (exit 1: it is not whole).
  const auto info = wbi::test::run_wbi({"bag", "info", out.string(), "--json"});
  EXPECT_EQ(info.code, 1) << info.output;
  EXPECT_TRUE(contains(info.output, "wbi/kill_me/sensors")) << info.output;
  EXPECT_TRUE(contains(info.output, "wbi bag: " + out.string() + ": file truncated"))
      << info.output;
}

// --split-size: several files, each readable alone, together every sample once.
// The size is above what every file repeats, the schemas (the full text of
// sensors.idl and commands.idl with common.idl: about 10 kB), else a file holds
// nothing else.
TEST_F(RecordPlay, SplitsIntoFilesThatEachStandAlone) {
  const auto out = file("split.mcap");
  ChildProcess talker(wbi::test::talker_program(), {"split_me", "0"});  // 100 Hz until stopped
  const auto run =
      wbi::test::run_wbi({"record", "-o", out.string(), "wbi/split_me/.*", "--split-size", "0.02",
                          "--compression", "none", "--duration", "2.5"});
  ASSERT_EQ(run.code, 0) << run.output;
  std::vector<std::uint32_t> sequences;
  std::size_t files = 0;
  for (std::size_t index = 0;; ++index) {
    const auto part = out.parent_path() / (out.stem().string() + "_" + std::to_string(index) +
                                           out.extension().string());
    if (!std::filesystem::exists(part)) {
      break;
    }
    ++files;
    const auto by_topic = wbi::test::messages_by_topic(part);
    std::filesystem::remove(part);
    ASSERT_EQ(by_topic.count("wbi/split_me/sensors"), 1u) << part;
    for (const auto& message : by_topic.at("wbi/split_me/sensors")) {
      sequences.push_back(message.sequence);
    }
  }
  EXPECT_GE(files, 2u) << run.output;
  ASSERT_GT(sequences.size(), 50u);
  for (std::size_t i = 0; i < sequences.size(); ++i) {
    ASSERT_EQ(sequences[i], i) << "every sample once, in order, across the files";
  }
}

// Spans between the second and the last arrival (the first may come from the
// writer's history, late).
double arrival_span_s(const std::vector<std::int64_t>& arrivals) {
  return 1e-9 * static_cast<double>(arrivals.back() - arrivals[1]);
}

TEST_F(RecordPlay, PlaysValuesInOrderWithRecordedTimingAtRates1And2) {
  const auto recording = file("timing.mcap");
  constexpr std::uint64_t kCount = 40;
  constexpr auto kPeriod = 25ms;
  wbi::test::write_pattern_recording(recording, {"play_t"}, kCount, kPeriod);
  const double expected_s = 1e-3 * static_cast<double>(kPeriod.count()) * (kCount - 2);
  wbi::dds::Participant participant("listener");
  std::map<double, double> span_by_rate;
  for (const double rate : {1.0, 2.0}) {
    wbi::test::SensorListener listener(participant, "play_t", "wbi/play_t/sensors");
    const auto run = wbi::test::run_wbi(
        {"play", recording.string(), "--rate", std::to_string(rate), "--wait-subscribers", "20"});
    ASSERT_EQ(run.code, 0) << run.output;
    ASSERT_TRUE(listener.wait_for(kCount, 10s)) << listener.received() << " of " << kCount;
    EXPECT_EQ(listener.seqs(), wbi::test::consecutive_seqs(0, kCount));
    EXPECT_EQ(listener.mismatch(), "");
    span_by_rate[rate] = arrival_span_s(listener.arrivals_ns());
    // Never faster than the recording over the rate: the player waits for each
    // message's time (a loaded machine only delays it).
    EXPECT_GT(span_by_rate[rate], 0.85 * expected_s / rate) << "rate " << rate;
  }
  // At rate 2 the 0.95 s of the recording play in less than 0.95 s (0.475 s
  // when on time), which rate 1 can never do. How close each rate keeps to its
  // spacing is a benchmark figure, not a check here: wbi_bench_record_play
  // (play_1khz, play_1khz_rate2: span_ratio, interval errors).
  EXPECT_LT(span_by_rate[2.0], expected_s) << "rate 1: " << span_by_rate[1.0] << " s";
  std::cout << "spans: rate 1 " << span_by_rate[1.0] << " s, rate 2 " << span_by_rate[2.0]
            << " s (recorded " << expected_s << " s)\n";
}

TEST_F(RecordPlay, RemapPublishesUnderTheNewName) {
  const auto recording = file("remap.mcap");
  wbi::test::write_pattern_recording(recording, {"remap_src"}, 20, 5ms);
  wbi::dds::Participant participant("listener");
  wbi::test::SensorListener listener(participant, "remap_src", "wbi/remapped/sensors");
  const auto run = wbi::test::run_wbi({"play", recording.string(), "--remap",
                                       "wbi/remap_src/sensors:=wbi/remapped/sensors",
                                       "--wait-subscribers", "20"});
  ASSERT_EQ(run.code, 0) << run.output;
  ASSERT_TRUE(listener.wait_for(20, 10s)) << listener.received() << "\n" << run.output;
  EXPECT_EQ(listener.seqs(), wbi::test::consecutive_seqs(0, 20));
  EXPECT_EQ(listener.mismatch(), "");
}

// record -> play -> record: the same payloads, in the same order, per topic.
TEST_F(RecordPlay, RecordPlayRecordKeepsEveryPayload) {
  const auto original = file("original.mcap");
  const auto again = file("again.mcap");
  wbi::test::write_pattern_recording(original, {"det_a", "det_b"}, 60, 4ms);
  ChildProcess recorder(wbi::test::wbi_program(), {"record", "-o", again.string(), "wbi/det_.*"});
  ASSERT_TRUE(recorder.wait_for_output("recording to", 20s)) << recorder.output();
  const auto run = wbi::test::run_wbi({"play", original.string(), "--wait-subscribers", "20"});
  ASSERT_EQ(run.code, 0) << run.output;
  // The player waited for every reader's acknowledgement before it exited.
  ASSERT_EQ(recorder.stop(SIGTERM, 20s), 0) << recorder.output();
  auto expected = wbi::test::messages_by_topic(original);
  auto recorded = wbi::test::messages_by_topic(again);
  ASSERT_EQ(recorded.size(), expected.size()) << recorder.output();
  for (const auto& [topic, messages] : expected) {
    const auto& got = recorded[topic];
    ASSERT_EQ(got.size(), messages.size()) << topic << "\n" << recorder.output();
    for (std::size_t i = 0; i < messages.size(); ++i) {
      ASSERT_EQ(got[i].data, messages[i].data) << topic << " message " << i;
      ASSERT_EQ(got[i].publish_time, messages[i].publish_time) << topic << " message " << i;
    }
  }
}

TEST_F(RecordPlay, PauseAndStepThroughTheControlTopic) {
  const auto recording = file("paused.mcap");
  wbi::test::write_pattern_recording(recording, {"step_me"}, 10, 5ms);
  wbi::dds::Participant participant("controller");
  wbi::test::SensorListener listener(participant, "step_me", "wbi/step_me/sensors");
  wbi::dds::Publisher<wbi::msg::PlaybackCommand> control(participant, "wbi/play/control",
                                                         wbi::dds::qos::kCommand);
  ChildProcess player(wbi::test::wbi_program(), {"play", recording.string(), "--paused"});
  ASSERT_TRUE(control.wait_for_subscribers(1, 20s)) << player.output();
  wbi::msg::PlaybackCommand command;
  // A command sent while the player's reader has not yet matched us is lost:
  // resend until it shows (a step sent twice steps twice, hence "at least").
  auto send_until = [&](wbi::msg::PlaybackAction action, std::size_t at_least) {
    command.action(action);
    for (int attempt = 0; attempt < 20; ++attempt) {
      control.publish(command);
      if (listener.wait_for(at_least, 500ms)) {
        return true;
      }
    }
    return false;
  };
  ASSERT_TRUE(send_until(wbi::msg::STEP, 1)) << player.output();
  const std::size_t after_step = listener.received();
  EXPECT_LT(after_step, 10u) << "paused: a step publishes one message";
  EXPECT_FALSE(listener.wait_for(after_step + 1, 300ms)) << "still paused after the step";
  ASSERT_TRUE(send_until(wbi::msg::RESUME, 10)) << player.output();
  EXPECT_EQ(player.wait(20s), std::optional<int>(0)) << player.output();
  EXPECT_EQ(listener.seqs(), wbi::test::consecutive_seqs(0, 10));
}

TEST_F(RecordPlay, BadArgumentsAndFilesGiveClearErrors) {
  const auto recording = file("good.mcap");
  wbi::test::write_pattern_recording(recording, {"bad_args"}, 3, 1ms);
  const auto garbage = file("garbage.mcap");
  {
    std::ofstream out(garbage);
    out << "this is not an MCAP file";
  }
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases{
      {{"record", "--all"}, "missing -o"},
      {{"record", "-o", file("x.mcap").string()}, "TOPIC_REGEX"},
      {{"record", "-o", file("y.mcap").string(), "("}, "bad topic regex '('"},
      {{"record", "-o", file("z.mcap").string(), "--all", "--compression", "rar"},
       "--compression must be none, zstd or lz4"},
      {{"record", "-o", "/nonexistent/dir/f.mcap", "--all"}, "/nonexistent/dir/f.mcap"},
      {{"play", garbage.string()}, "bad magic"},
      {{"play", file("missing.mcap").string()}, "no such file"},
      {{"play", recording.string(), "--rate", "0"}, "--rate must be > 0"},
      {{"play", recording.string(), "--realtime-priority", "100"},
       "--realtime-priority must be in [0, 99]"},
      {{"play", recording.string(), "--spin-us", "-1"}, "--spin-us must be in [0, 1000000]"},
      {{"play", recording.string(), "--start-offset", "5"}, "past the end of the recording"},
      {{"play", recording.string(), "--remap", "nothing"}, "FROM:=TO"},
      {{"play", recording.string(), "--remap", "wbi/none:=wbi/x"}, "no topic 'wbi/none'"},
      {{"play", recording.string(), "--topics", "wbi/none"}, "no topic to play"},
  };
  for (const auto& c : cases) {
    const auto run = wbi::test::run_wbi(c.args, 20s);
    EXPECT_EQ(run.code, 1) << c.args[0] << " " << c.args.back() << ": " << run.output;
    EXPECT_TRUE(contains(run.output, c.message))
        << "expected '" << c.message << "' in: " << run.output;
  }
}

}  // namespace
