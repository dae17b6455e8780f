// Issue 8, item 4: record the sensors of a lockstep run, replay them into a
// fresh estimator, and get the live run's estimates bit for bit.
//
// Live: `wbi record` of wbi/arm/{description,sensors,state} while `wbi launch`
// runs robot + estimator + controller in lockstep (determinism_lockstep.yaml);
// the controller starts only once the recorder has subscribed to all three.
// Replay: the "estimator" process of the same file alone (wbi_host), no robot;
// `wbi play` of the recorded description and sensors at half speed; `wbi
// record` of the new wbi/arm/state. Then every replayed StateEstimate must
// have the CDR bytes of the live one with the same source stamp.
//
// What makes it deterministic: the estimator works on the samples' source
// stamps, never on arrival time; lockstep hands it one sensor sample at a time
// in the live run; reliable streams and a replay slower than the live run
// leave no sample behind (checked: one estimate per sensor sample in both
// runs); and a sample that comes before the description is estimated once the
// description is there (the replayed description may come just after the
// first sample, never after the second, which the robot sent only once the
// controller had started).
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <wbi/msg/playback.h>
#include <wbi/msg/state.h>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "record_play_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

constexpr std::size_t kTicks = 1000;              // determinism_lockstep.yaml
constexpr std::int64_t kLastStamp = 999'000'000;  // tick 999 of 1 ms
constexpr const char* kSensors = "wbi/arm/sensors";
constexpr const char* kState = "wbi/arm/state";

std::filesystem::path deploy_file() {
  return wbi::test::source_dir() / "tests" / "recording" / "determinism_lockstep.yaml";
}

// Waits until `state` has delivered the estimate of the last tick.
bool wait_for_last_estimate(const wbi::dds::Subscriber<wbi::msg::StateEstimate>& state,
                            std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  wbi::dds::Received<wbi::msg::StateEstimate> latest;
  while (std::chrono::steady_clock::now() < deadline) {
    if (state.latest_into(latest) && latest.sample.header().stamp_ns() >= kLastStamp) {
      return true;
    }
    state.wait_newer(latest, state.count(), 200ms);
  }
  return false;
}

// The recorder's progress line counts what it has received: wait for `count`
// so that stopping it loses nothing still in flight.
bool wait_for_recorded(ChildProcess& recorder, std::size_t count) {
  return recorder.wait_for_output("messages " + std::to_string(count) + "  ", 30s);
}

// The messages of one topic keyed by publish time (= Header.stamp_ns); fails on a repeated stamp.
std::map<std::uint64_t, std::vector<std::uint8_t>> by_stamp(
    const std::vector<wbi::test::SampleMessage>& messages) {
  std::map<std::uint64_t, std::vector<std::uint8_t>> out;
  for (const auto& message : messages) {
    EXPECT_TRUE(out.emplace(message.publish_time, message.data).second)
        << message.topic << ": stamp " << message.publish_time << " twice";
  }
  return out;
}

std::vector<std::uint64_t> tick_stamps() {
  std::vector<std::uint64_t> stamps;
  for (std::uint64_t tick = 0; tick < kTicks; ++tick) {
    stamps.push_back(tick * 1'000'000);
  }
  return stamps;
}

template <class Map>
std::vector<std::uint64_t> keys(const Map& map) {
  std::vector<std::uint64_t> out;
  for (const auto& [key, value] : map) {
    out.push_back(key);
  }
  return out;
}

TEST(ReplayDeterminism, ReplayedSensorsGiveTheLiveEstimatesBitForBit) {
  const wbi::test::TempDir dir;
  const auto live_file = dir / "live.mcap";
  const auto replay_file = dir / "replay.mcap";
  wbi::dds::Participant participant("observer");

  {  // The live run.
    wbi::dds::Subscriber<wbi::msg::StateEstimate> state(participant, kState,
                                                        wbi::dds::qos::kStream);
    ChildProcess recorder(wbi::test::wbi_program(), {"record", "-o", live_file.string(),
                                                     "wbi/arm/(description|sensors|state)"});
    ASSERT_TRUE(recorder.wait_for_output("recording to", 20s)) << recorder.output();
    ChildProcess launch(wbi::test::wbi_program(), {"launch", deploy_file().string()});
    // The controller, and so the lockstep run, starts once the recorder is
    // subscribed to all three topics (determinism_lockstep.yaml).
    for (const char* topic : {"wbi/arm/description", kSensors, kState}) {
      ASSERT_TRUE(recorder.wait_for_output(std::string("recording ") + topic + " ", 60s))
          << recorder.output() << launch.output();
    }
    const wbi::dds::Publisher<wbi::msg::PlaybackCommand> recorder_ready(
        participant, "test/recorder_ready", wbi::dds::qos::kCommand);
    ASSERT_TRUE(wait_for_last_estimate(state, 120s)) << launch.output();
    // Description, then a sensor sample and its estimate per tick.
    EXPECT_TRUE(wait_for_recorded(recorder, 1 + 2 * kTicks)) << recorder.output();
    launch.stop(SIGINT, 20s);
    ASSERT_EQ(recorder.stop(SIGINT, 20s), 0) << recorder.output();
    EXPECT_EQ(launch.output().find("not answered"), std::string::npos)
        << "a lockstep tick timed out:\n"
        << launch.output();
  }
  auto live = wbi::test::messages_by_topic(live_file);
  const auto live_sensors = by_stamp(live[kSensors]);
  const auto live_state = by_stamp(live[kState]);
  ASSERT_EQ(live["wbi/arm/description"].size(), 1u);
  ASSERT_EQ(keys(live_sensors), tick_stamps()) << "the recorder missed sensor samples";
  ASSERT_EQ(keys(live_state), tick_stamps()) << "the live estimator skipped samples";
  ASSERT_NE(live_state.begin()->second, live_state.rbegin()->second) << "the estimate never moved";

  {  // The replay, without the robot and the controller.
    wbi::dds::Subscriber<wbi::msg::StateEstimate> state(participant, kState,
                                                        wbi::dds::qos::kStream);
    ChildProcess estimator(wbi::test::binary_dir() / "bin" / "wbi_host",
                           {deploy_file().string(), "--process", "estimator"});
    ASSERT_TRUE(estimator.wait_for_output("wbi_host: running", 30s)) << estimator.output();
    ChildProcess recorder(wbi::test::wbi_program(), {"record", "-o", replay_file.string(), kState});
    // Subscribed to the estimator's state before the first estimate is made.
    ASSERT_TRUE(recorder.wait_for_output(std::string("recording ") + kState, 20s))
        << recorder.output();
    const auto play =
        wbi::test::run_wbi({"play", live_file.string(), "--topics", "wbi/arm/(description|sensors)",
                            "--rate", "0.5", "--wait-subscribers", "20"},
                           180s);
    ASSERT_EQ(play.code, 0) << play.output;
    EXPECT_TRUE(wait_for_last_estimate(state, 30s)) << estimator.output();
    EXPECT_TRUE(wait_for_recorded(recorder, kTicks)) << recorder.output();
    ASSERT_EQ(recorder.stop(SIGINT, 20s), 0) << recorder.output();
  }
  auto replay = wbi::test::messages_by_topic(replay_file);
  const auto replay_state = by_stamp(replay[kState]);
  ASSERT_EQ(keys(replay_state), tick_stamps()) << "the replayed estimator skipped samples";
  std::vector<std::uint64_t> differing;
  for (const auto& [stamp, bytes] : live_state) {
    if (replay_state.at(stamp) != bytes) {
      differing.push_back(stamp);
    }
  }
  EXPECT_TRUE(differing.empty()) << differing.size() << " of " << kTicks
                                 << " estimates differ, the first at stamp " << differing.front()
                                 << " ns";
}

}  // namespace
