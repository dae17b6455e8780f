// Tick pacers: when may tick k of a simulated robot's loop, whose sensors are
// out, apply its commands and step the simulation?
// Not a clock: runtime::Clock says what time it is; a pacer only holds tick k back.
//   LockstepPacer  once every named controller has sent its command for tick k
//                  (ActuatorCommand.tick), or after a timeout (counted, with a
//                  warning): deterministic, as fast as the controllers allow;
//   RealTimePacer  at start + (k + 1)·period on the wall clock (steady time):
//                  the simulation paced at real time, whatever the controllers do.
//                  A tick late by up to max_lag is caught up (scheduling jitter);
//                  a longer delay (the process stalled: SIGSTOP, a debugger, swap)
//                  is not: the schedule restarts from now, so the simulation pauses
//                  with the process instead of running the missed time in a burst
//                  under commands computed before the stall.
// A real robot needs neither: the runner's periodic cycle paces it
// (robot_driver.cpp). A stall that gets its line, and a lockstep tick not
// answered in time, are also LOOP_STALL events (warning) on the owner's log.
//
// Threads: wait() runs on the driver's loop; observe() on DDS threads; stop()
// on the thread that deactivates. wait() never allocates (a timeout's warning
// excepted).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <wbi/msg/commands.h>
#include <wbi/runtime/duration_histogram.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/status_report.hpp>

namespace wbi::robot {

class TickPacer {
 public:
  virtual ~TickPacer() = default;
  // Before the first tick of an activation.
  virtual void start() = 0;
  // Returns when tick `tick` may go on (its commands applied, the simulation stepped).
  virtual void wait(std::uint64_t tick) = 0;
  // Ends the wait in progress, and every later one at once, until start().
  virtual void stop() = 0;
  // Every command that reached the actuator side, accepted or not (a DDS thread);
  // written_ns: its DDS source timestamp (the system clock at the writer), 0: unknown.
  virtual void observe(const wbi::msg::ActuatorCommand& /*command*/,
                       std::int64_t /*written_ns*/ = 0) {}
  virtual bool lockstep() const = 0;
  // What the pacer saw since start(), one line for the end of a run, or "" (the
  // loop's thread).
  virtual std::string summary() const { return ""; }
};

// When a real-time tick is due: the arithmetic of RealTimePacer, on times given
// to it (tested without waiting).
class RealTimeSchedule {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;
  RealTimeSchedule(std::chrono::nanoseconds period, std::chrono::nanoseconds max_lag)
      : period_(period), max_lag_(max_lag) {}
  void start(TimePoint now) { anchor_ = now; }
  // When tick `tick` may go on, seen at `now`: anchor + (tick + 1)·period, or
  // `now` when that is more than max_lag ago; then the schedule restarts from
  // `now`, and `dropped` is the time not caught up (else zero).
  TimePoint due(std::uint64_t tick, TimePoint now, std::chrono::nanoseconds& dropped);

 private:
  const std::chrono::nanoseconds period_;
  const std::chrono::nanoseconds max_lag_;
  TimePoint anchor_;  // tick k is due at anchor_ + (k + 1)·period_
};

// Whether a stall gets its line on stderr: one of at least `always_from` (the
// process was stopped, not jittering) always does; shorter ones at most one a
// `period` (a VM that stalls 20-30 ms every few seconds would otherwise fill
// the log), the ones between counted into the next line. Tested on given times.
class StallLines {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;
  StallLines(std::chrono::nanoseconds period, std::chrono::nanoseconds always_from)
      : period_(period), always_from_(always_from) {}
  // True when the stall of `length` seen at `now` is to be printed; then
  // `unprinted` is the number of stalls since the last printed one that were not.
  bool print(TimePoint now, std::chrono::nanoseconds length, std::uint64_t& unprinted);

 private:
  const std::chrono::nanoseconds period_;
  const std::chrono::nanoseconds always_from_;
  std::optional<TimePoint> last_;
  std::uint64_t unprinted_ = 0;
};

class RealTimePacer final : public TickPacer {
 public:
  // who: names the robot in the stall message; stalls: the status counter of
  // delays not caught up; events: where a stall's event goes.
  RealTimePacer(std::chrono::nanoseconds period, std::chrono::nanoseconds max_lag, std::string who,
                runtime::StatusCounter& stalls, runtime::EventLog& events)
      : schedule_(period, max_lag), who_(std::move(who)), stalls_(stalls), events_(events) {}
  void start() override;
  void wait(std::uint64_t tick) override;
  void stop() override;
  bool lockstep() const override { return false; }
  // "real time: B of N ticks behind their deadline (P %), S stall(s) not caught up":
  // a tick is behind when its time had passed before the loop got to wait for it
  // (the previous tick's work, or the scheduler, overran the period).
  std::string summary() const override;

 private:
  RealTimeSchedule schedule_;                               // the driver's loop only
  std::uint64_t ticks_ = 0, behind_ = 0, stalls_seen_ = 0;  // since start(); loop only
  StallLines stall_lines_{std::chrono::seconds(10), std::chrono::milliseconds(100)};  // loop only
  const std::string who_;
  runtime::StatusCounter& stalls_;
  runtime::EventLog& events_;
  std::mutex mutex_;  // guards stopped_
  std::condition_variable stopped_changed_;
  bool stopped_ = false;
};

struct LockstepOptions {
  std::vector<std::string> controllers;  // ActuatorCommand.controller names to wait for
  double timeout_s = 2.0;                // longest wait for one tick's commands
  double start_timeout_s = 60.0;         // longest wait for tick 0's (the controllers start)
};

class LockstepPacer final : public TickPacer {
 public:
  // period: the simulation's step; who: names the robot in the timeout warning,
  // e.g. "sim_robot 'arm'"; timeouts: the status counter of ticks not answered in
  // time; events: where a timeout's event goes.
  LockstepPacer(LockstepOptions options, std::chrono::nanoseconds period, std::string who,
                runtime::StatusCounter& timeouts, runtime::EventLog& events);
  void start() override;
  void wait(std::uint64_t tick) override;
  void stop() override;
  void observe(const wbi::msg::ActuatorCommand& command, std::int64_t written_ns = 0) override;
  bool lockstep() const override { return true; }
  // The run's speed and where a tick went, from tick 1 on (tick 0 waits for the
  // controllers to start): "lockstep: simulated 21.000 s in 24.3 s wall: 0.86×
  // real time; per tick 1.16 ms: waiting for the controllers' commands mean
  // 1.02 ms (p99 1.41 ms), the robot's own work mean 0.14 ms (p99 0.21 ms)".
  // The wait is the round trip sensors → … → commands through every other
  // process; the robot's work is its step, its sensors and ground truth out,
  // and the commands in. Where the commands' DDS source timestamps are known
  // the wait is split at the writing of the tick's last command: "; the wait:
  // sensors out to the last command written mean … ms (p99 … ms), its delivery
  // to the robot mean … ms (p99 … ms)" (one clock: the controllers on this host,
  // or hosts with synchronised clocks).
  std::string summary() const override;

 private:
  bool all_answered(std::uint64_t tick) const;  // with mutex_ held
  void time_tick(std::chrono::steady_clock::time_point called,
                 std::chrono::steady_clock::time_point answered, std::int64_t called_ns,
                 std::int64_t answered_ns, std::int64_t written_ns);  // the loop only

  const LockstepOptions options_;
  const std::string who_;
  runtime::StatusCounter& timeouts_;
  runtime::EventLog& events_;
  std::mutex mutex_;  // guards answered_, stopped_, written_tick_, written_ns_
  std::condition_variable changed_;
  std::map<std::string, std::int64_t> answered_;     // newest tick answered per controller
  std::int64_t written_tick_ = -1, written_ns_ = 0;  // newest tick, its last command's writing
  bool stopped_ = false;
  // The loop's thread only: when the first and the previous tick were
  // answered, the ticks timed, the waits and the robot's work between them.
  const std::chrono::nanoseconds period_;
  std::chrono::steady_clock::time_point first_answered_, last_answered_;
  std::uint64_t timed_ticks_ = 0;
  runtime::DurationHistogram waits_, work_, to_written_, delivered_;
};

}  // namespace wbi::robot
