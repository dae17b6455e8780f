// The real-time pacer's schedule on given times: jitter is caught up, a stall
// is not (the simulation pauses with its process instead of stepping the
// missed time in a burst); a stall's line on stderr at most once a period; the
// pacer's end-of-run line counts the ticks behind their deadline. The lockstep
// pacer counts a command with no tick (a mode switch) as no answer.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include <string>

#include <wbi/dds/source_clock.hpp>
#include <wbi/msg/wire_vocabulary.hpp>
#include <wbi/runtime/status_report.hpp>

#include "tick_pacer.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::robot::RealTimeSchedule;

constexpr auto kPeriod = std::chrono::nanoseconds(1ms);
constexpr auto kMaxLag = std::chrono::nanoseconds(20ms);
const RealTimeSchedule::TimePoint kStart{std::chrono::seconds(100)};

TEST(RealTimeSchedule, TicksAreDueOnePeriodApartFromTheStart) {
  RealTimeSchedule schedule(kPeriod, kMaxLag);
  schedule.start(kStart);
  std::chrono::nanoseconds dropped{};
  EXPECT_EQ(schedule.due(0, kStart, dropped), kStart + 1ms);
  EXPECT_EQ(schedule.due(9, kStart + 5ms, dropped), kStart + 10ms);
  EXPECT_EQ(dropped.count(), 0);
}

TEST(RealTimeSchedule, JitterWithinTheMaxLagIsCaughtUp) {
  RealTimeSchedule schedule(kPeriod, kMaxLag);
  schedule.start(kStart);
  std::chrono::nanoseconds dropped{};
  // Tick 4 seen 15 ms after its time: due in the past (no wait), schedule kept.
  EXPECT_EQ(schedule.due(4, kStart + 20ms, dropped), kStart + 5ms);
  EXPECT_EQ(dropped.count(), 0);
  EXPECT_EQ(schedule.due(5, kStart + 20ms, dropped), kStart + 6ms);
}

TEST(RealTimeSchedule, AStallIsNotCaughtUp) {
  RealTimeSchedule schedule(kPeriod, kMaxLag);
  schedule.start(kStart);
  std::chrono::nanoseconds dropped{};
  ASSERT_EQ(schedule.due(4, kStart + 5ms, dropped), kStart + 5ms);
  // The process stopped for a second after tick 4: tick 5 is due at once, and
  // the ticks after it one period apart again, not in a burst.
  const auto resumed = kStart + 1006ms;
  EXPECT_EQ(schedule.due(5, resumed, dropped), resumed);
  EXPECT_EQ(dropped, std::chrono::nanoseconds(1000ms));
  EXPECT_EQ(schedule.due(6, resumed, dropped), resumed + 1ms);
  EXPECT_EQ(dropped.count(), 0);
  EXPECT_EQ(schedule.due(10, resumed + 1ms, dropped), resumed + 5ms);
}

TEST(RealTimeSchedule, ZeroMaxLagCatchesNothingUp) {
  RealTimeSchedule schedule(kPeriod, std::chrono::nanoseconds(0));
  schedule.start(kStart);
  std::chrono::nanoseconds dropped{};
  EXPECT_EQ(schedule.due(0, kStart + 3ms, dropped), kStart + 3ms);
  EXPECT_EQ(dropped, std::chrono::nanoseconds(2ms));
  EXPECT_EQ(schedule.due(1, kStart + 3ms, dropped), kStart + 4ms);
}

using wbi::robot::StallLines;

constexpr auto kJitter = std::chrono::nanoseconds(25ms);

TEST(StallLines, TheFirstStallIsPrintedThenAtMostOneLineAPeriod) {
  StallLines lines(10s, 100ms);
  std::uint64_t unprinted = 99;
  EXPECT_TRUE(lines.print(kStart, kJitter, unprinted));
  EXPECT_EQ(unprinted, 0u);
  // Three more within 10 s: counted, not printed.
  EXPECT_FALSE(lines.print(kStart + 1s, kJitter, unprinted));
  EXPECT_FALSE(lines.print(kStart + 5s, kJitter, unprinted));
  EXPECT_FALSE(lines.print(kStart + 9999ms, kJitter, unprinted));
  // The next one after 10 s is printed and says how many were not.
  EXPECT_TRUE(lines.print(kStart + 10s, kJitter, unprinted));
  EXPECT_EQ(unprinted, 3u);
  // The count starts again from there.
  EXPECT_FALSE(lines.print(kStart + 11s, kJitter, unprinted));
  EXPECT_TRUE(lines.print(kStart + 30s, kJitter, unprinted));
  EXPECT_EQ(unprinted, 1u);
}

TEST(StallLines, AStoppedProcessIsAlwaysPrinted) {
  StallLines lines(10s, 100ms);
  std::uint64_t unprinted = 0;
  EXPECT_TRUE(lines.print(kStart, kJitter, unprinted));
  EXPECT_FALSE(lines.print(kStart + 1s, kJitter, unprinted));
  // A 1 s stop right after: printed at once, with the jitter it follows.
  EXPECT_TRUE(lines.print(kStart + 2s, std::chrono::nanoseconds(1s), unprinted));
  EXPECT_EQ(unprinted, 1u);
}

// Tick 4 is waited for (due 5 ms after the start); tick 1, due 2 ms after the
// start, comes when those 5 ms have passed: behind its deadline, caught up.
TEST(RealTimePacer, CountsTheTicksBehindTheirDeadline) {
  wbi::runtime::StatusCounter stalls;
  wbi::runtime::EventLog events;
  wbi::robot::RealTimePacer pacer(kPeriod, kMaxLag, "sim_robot 'arm'", stalls, events);
  pacer.start();
  pacer.wait(4);
  pacer.wait(1);
  const std::string line = pacer.summary();
  EXPECT_NE(line.find("real time: "), std::string::npos) << line;
  EXPECT_NE(line.find(" of 2 ticks behind their deadline ("), std::string::npos) << line;
  EXPECT_EQ(line.find("real time: 0 of"), std::string::npos) << "tick 1 came late: " << line;
  EXPECT_NE(line.find("0 stall(s) not caught up"), std::string::npos) << line;
  pacer.start();  // a new activation counts anew
  EXPECT_NE(pacer.summary().find("real time: 0 of 0 ticks"), std::string::npos);
}

// A controller's start-up mode switch carries no tick (docs/conventions.md):
// it must not answer tick 0, or the simulation steps it before the first
// command computed from a sample, or after, as timing decides.
TEST(LockstepPacer, ACommandWithNoTickAnswersNothing) {
  wbi::runtime::StatusCounter timeouts;
  wbi::runtime::EventLog events;
  wbi::robot::LockstepPacer pacer({{"balance"}, 0.05, 0.05}, std::chrono::milliseconds(1),
                                  "sim_robot 'humanoid'", timeouts, events);
  pacer.start();
  wbi::msg::ActuatorCommand command;
  command.controller("balance");
  command.tick(wbi::msg::kNoTick);
  pacer.observe(command);
  pacer.wait(0);
  EXPECT_EQ(timeouts.value(), 1u) << "tick 0 was taken as answered by a command with no tick";
  wbi::runtime::EventRecord event;
  ASSERT_TRUE(events.pop(event)) << "a tick not answered in time is an event";
  EXPECT_EQ(event.kind, wbi::EventKind::loop_stall);
  command.tick(0);
  pacer.observe(command);
  pacer.wait(0);
  EXPECT_EQ(timeouts.value(), 1u) << "tick 0 not answered by a command for it";
  command.tick(wbi::msg::kNoTick);  // a mode switch later on: tick 1 is still open
  pacer.observe(command);
  pacer.wait(1);
  EXPECT_EQ(timeouts.value(), 2u);
}

}  // namespace

// The end-of-run line of a lockstep run: simulated time from the ticks stepped
// after the first (which waits for the controllers to start), the wall time
// they took, and where a tick went: here the "robot's work" between ticks is a
// 2 ms sleep, and the commands are in before each wait.
TEST(LockstepPacer, ReportsTheRunsSpeedAndWhereATickWent) {
  wbi::runtime::StatusCounter timeouts;
  wbi::runtime::EventLog events;
  wbi::robot::LockstepPacer pacer({{"balance"}, 1.0, 1.0}, std::chrono::milliseconds(1),
                                  "sim_robot 'humanoid'", timeouts, events);
  pacer.start();
  EXPECT_EQ(pacer.summary(), "") << "no tick timed yet";
  wbi::msg::ActuatorCommand command;
  command.controller("balance");
  for (std::uint64_t tick = 0; tick <= 10; ++tick) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // the work being timed
    command.tick(tick);
    pacer.observe(command);
    pacer.wait(tick);
  }
  const std::string line = pacer.summary();
  EXPECT_EQ(line.rfind("lockstep: simulated 0.010 s in ", 0), 0u) << line;
  double wall_s = 0.0, speed = 0.0, tick_ms = 0.0, wait_ms = 0.0, wait_p99 = 0.0, work_ms = 0.0;
  ASSERT_EQ(std::sscanf(line.c_str(),
                        "lockstep: simulated 0.010 s in %lf s wall: %lfx real time; per tick %lf "
                        "ms: waiting for the controllers' commands mean %lf ms (p99 %lf ms), the "
                        "robot's own work mean %lf ms",
                        &wall_s, &speed, &tick_ms, &wait_ms, &wait_p99, &work_ms),
            6)
      << line;
  EXPECT_GE(work_ms, 2.0) << line;
  EXPECT_LT(wait_ms, work_ms) << "the commands were in before each wait: " << line;
  EXPECT_NEAR(tick_ms, wait_ms + work_ms, 0.01) << line;
  EXPECT_LT(speed, 0.5) << "a 1 ms tick took over 2 ms: " << line;
  EXPECT_EQ(timeouts.value(), 0u);
  pacer.start();  // a new activation counts anew
  EXPECT_EQ(pacer.summary(), "");
}

// With the commands' writing times the wait is split there: a controller that
// writes each tick's command 5 ms after the previous one, while the robot does
// nothing between waits, spends most of the wait before its writing.
TEST(LockstepPacer, SplitsTheWaitWhereTheCommandWasWritten) {
  wbi::runtime::StatusCounter timeouts;
  wbi::runtime::EventLog events;
  wbi::robot::LockstepPacer pacer({{"balance"}, 1.0, 1.0}, std::chrono::milliseconds(1),
                                  "sim_robot 'humanoid'", timeouts, events);
  pacer.start();
  constexpr std::uint64_t kTicks = 8;
  std::thread controller([&] {
    wbi::msg::ActuatorCommand command;
    command.controller("balance");
    for (std::uint64_t tick = 0; tick <= kTicks; ++tick) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));  // the compute being timed
      command.tick(tick);
      pacer.observe(command, wbi::dds::source_clock_now_ns());
    }
  });
  for (std::uint64_t tick = 0; tick <= kTicks; ++tick) {
    pacer.wait(tick);
  }
  controller.join();
  const std::string line = pacer.summary();
  const auto split = line.find("; the wait: sensors out to the last command written mean ");
  ASSERT_NE(split, std::string::npos) << line;
  double to_written_ms = 0.0, to_written_p99 = 0.0, delivered_ms = 0.0;
  ASSERT_EQ(std::sscanf(line.c_str() + split,
                        "; the wait: sensors out to the last command written mean %lf ms (p99 %lf "
                        "ms), its delivery to the robot mean %lf ms",
                        &to_written_ms, &to_written_p99, &delivered_ms),
            3)
      << line;
  EXPECT_GT(to_written_ms, 2.5) << line;
  EXPECT_LT(delivered_ms, to_written_ms) << line;
  EXPECT_EQ(timeouts.value(), 0u);
}
