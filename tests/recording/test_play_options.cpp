// `wbi play --loop`, `--start-offset` and `--clock`, as a user runs them: the
// player as a `wbi` process, subscribers in this process, recordings of the
// talker's pattern samples (each value follows from its sequence number).
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <wbi/msg/status.h>
#include <wbi/dds/subscriber.hpp>

#include "record_play_support.hpp"
#include "sensor_listener.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

class PlayOptions : public ::testing::Test {
 protected:
  wbi::test::TempDir dir_;
  wbi::dds::Participant participant_{"listener"};
};

// Every pass publishes the file again, from its first message, in order.
TEST_F(PlayOptions, LoopPlaysTheFileAgainInOrder) {
  constexpr std::uint64_t kCount = 10;
  const auto recording = dir_ / "loop.mcap";
  wbi::test::write_pattern_recording(recording, {"loop_me"}, kCount, 5ms);
  wbi::test::SensorListener listener(participant_, "loop_me", "wbi/loop_me/sensors");
  ChildProcess player(wbi::test::wbi_program(),
                      {"play", recording.string(), "--loop", "--wait-subscribers", "20"});
  ASSERT_TRUE(listener.wait_for(2 * kCount + kCount / 2, 30s))
      << listener.received() << " received\n"
      << player.output();
  EXPECT_TRUE(player.running()) << "--loop ended by itself:\n" << player.output();
  EXPECT_EQ(player.stop(SIGINT, 10s), 130) << player.output();
  const auto seqs = listener.seqs();
  ASSERT_GT(seqs.size(), 2 * kCount);
  for (std::size_t i = 0; i < seqs.size(); ++i) {
    ASSERT_EQ(seqs[i], i % kCount) << "message " << i << " of the loop";
  }
  EXPECT_EQ(listener.mismatch(), "");
}

// Samples stamped 1 ms apart, logged 1 ms apart: an offset of 49.5 ms starts
// at the sample stamped 50 ms, and nothing before it is published. Played at a
// real-time priority (granted or refused with a warning: the same messages)
// and a longer spin.
TEST_F(PlayOptions, StartOffsetSkipsTheFirstSeconds) {
  constexpr std::uint64_t kCount = 100;
  const auto recording = dir_ / "offset.mcap";
  wbi::test::write_pattern_recording(recording, {"offset_me"}, kCount, 1ms);
  wbi::test::SensorListener listener(participant_, "offset_me", "wbi/offset_me/sensors");
  const auto run = wbi::test::run_wbi({"play", recording.string(), "--start-offset", "0.0495",
                                       "--rate", "0.25", "--wait-subscribers", "20",
                                       "--realtime-priority", "10", "--spin-us", "500"});
  ASSERT_EQ(run.code, 0) << run.output;
  ASSERT_TRUE(listener.wait_for(kCount - 50, 10s)) << listener.received() << "\n" << run.output;
  const auto seqs = listener.seqs();
  EXPECT_GE(seqs.front() * 1'000'000, 49'500'000u) << "first source stamp before start + offset";
  EXPECT_EQ(seqs, wbi::test::consecutive_seqs(50, kCount - 50));
  EXPECT_EQ(listener.mismatch(), "");
  EXPECT_NE(run.output.find("played 50 messages"), std::string::npos) << run.output;
}

struct ClockTick {
  std::int64_t time_ns;
  std::uint64_t tick;
  std::int64_t step_ns;
  bool lockstep;
  std::int64_t received_ns;
};

// --clock: a SimulationClock on wbi/clock every 10 ms of recorded time (the
// default 100 Hz), carrying the recording's log time, paced like the messages.
TEST_F(PlayOptions, ClockPublishesTheRecordedTime) {
  constexpr std::uint64_t kCount = 40;
  constexpr auto kPeriod = 25ms;
  const auto recording = dir_ / "clock.mcap";
  wbi::test::write_pattern_recording(recording, {"clock_me"}, kCount, kPeriod);
  const wbi::mcap::Reader reader(recording);
  const std::uint64_t start = reader.info().statistics.message_start_time;
  const std::uint64_t end = reader.info().statistics.message_end_time;  // start + 975 ms

  std::mutex mutex;
  std::vector<ClockTick> ticks;
  wbi::dds::Subscriber<wbi::msg::SimulationClock> clock(
      participant_, "wbi/clock", wbi::dds::qos::kStream,
      [&](const wbi::msg::SimulationClock& c, const wbi::dds::detail::SampleInfo& info) {
        std::lock_guard lock(mutex);
        ticks.push_back({c.time_ns(), c.tick(), c.step_ns(), c.lockstep(), info.received_ns});
      });
  wbi::test::SensorListener listener(participant_, "clock_me", "wbi/clock_me/sensors");
  const auto run =
      wbi::test::run_wbi({"play", recording.string(), "--clock", "--wait-subscribers", "20"});
  ASSERT_EQ(run.code, 0) << run.output;
  ASSERT_TRUE(listener.wait_for(kCount, 10s)) << listener.received() << "\n" << run.output;
  EXPECT_EQ(listener.seqs(), wbi::test::consecutive_seqs(0, kCount));

  constexpr std::uint64_t kClockPeriod = 10'000'000;
  const std::uint64_t expected_ticks = (end - start) / kClockPeriod + 1;  // 0, 10, ..., 970 ms
  // The player waited for the acknowledgement of its last tick before it exited.
  wbi::dds::Received<wbi::msg::SimulationClock> latest;
  for (int attempt = 0; attempt < 50 && clock.count() < expected_ticks; ++attempt) {
    clock.wait_newer(latest, clock.count(), 100ms);
  }
  std::lock_guard lock(mutex);
  ASSERT_EQ(ticks.size(), expected_ticks) << run.output;
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    ASSERT_EQ(ticks[k].time_ns, static_cast<std::int64_t>(start + k * kClockPeriod))
        << "tick " << k;
    ASSERT_EQ(ticks[k].tick, k);
    ASSERT_EQ(ticks[k].step_ns, static_cast<std::int64_t>(kClockPeriod));
    ASSERT_FALSE(ticks[k].lockstep);
  }
  // Paced with the recording, not dumped at once (a loose bound for a loaded machine).
  const double recorded_s = 1e-9 * static_cast<double>(ticks.back().time_ns - ticks[1].time_ns);
  const double played_s =
      1e-9 * static_cast<double>(ticks.back().received_ns - ticks[1].received_ns);
  EXPECT_GT(played_s, 0.85 * recorded_s);
}

}  // namespace
