#include "tick_pacer.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <wbi/dds/source_clock.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "wbi/runtime/console_line.hpp"

namespace wbi::robot {

RealTimeSchedule::TimePoint RealTimeSchedule::due(std::uint64_t tick, TimePoint now,
                                                  std::chrono::nanoseconds& dropped) {
  // From the anchor, not from the previous tick: jitter is caught up, no drift.
  const TimePoint due = anchor_ + period_ * static_cast<std::int64_t>(tick + 1);
  dropped = std::chrono::nanoseconds(0);
  if (now - due <= max_lag_) {
    return due;
  }
  dropped = std::chrono::duration_cast<std::chrono::nanoseconds>(now - due);
  anchor_ = now - period_ * static_cast<std::int64_t>(tick + 1);  // tick is due now
  return now;
}

void RealTimePacer::start() {
  std::lock_guard lock(mutex_);
  stopped_ = false;
  ticks_ = behind_ = stalls_seen_ = 0;
  schedule_.start(std::chrono::steady_clock::now());
}

std::string RealTimePacer::summary() const {
  char line[160];
  std::snprintf(
      line, sizeof line,
      "real time: %llu of %llu ticks behind their deadline (%.2f %%), %llu stall(s) "
      "not caught up",
      static_cast<unsigned long long>(behind_), static_cast<unsigned long long>(ticks_),
      ticks_ > 0 ? 100.0 * static_cast<double>(behind_) / static_cast<double>(ticks_) : 0.0,
      static_cast<unsigned long long>(stalls_seen_));
  return line;
}

bool StallLines::print(TimePoint now, std::chrono::nanoseconds length, std::uint64_t& unprinted) {
  if (length < always_from_ && last_ && now - *last_ < period_) {
    ++unprinted_;
    return false;
  }
  last_ = now;
  unprinted = unprinted_;
  unprinted_ = 0;
  return true;
}

void RealTimePacer::wait(std::uint64_t tick) {
  std::chrono::nanoseconds dropped;
  const auto now = std::chrono::steady_clock::now();
  const auto due = schedule_.due(tick, now, dropped);
  ++ticks_;
  if (due < now || dropped.count() > 0) {
    ++behind_;
  }
  std::uint64_t unprinted = 0;
  if (dropped.count() > 0) {
    ++stalls_seen_;
    stalls_.add();  // every stall, printed or not: the status counter real_time_stalls
    if (stall_lines_.print(now, dropped, unprinted)) {
      std::ostringstream line;
      line << who_ << ": tick " << tick << " came "
           << std::chrono::duration<double>(dropped).count()
           << " s late (the process stalled?): the simulation paused with it, the time "
              "is not caught up";
      if (unprinted > 0) {
        line << " (" << unprinted << " more stall(s) since the last such line)";
      }
      const std::string text = line.str();
      runtime::print_line(stderr, text);
      events_.emit(EventSeverity::warning, EventKind::loop_stall, text);
    }
  }
  std::unique_lock lock(mutex_);
  stopped_changed_.wait_until(lock, due, [this] { return stopped_; });
}

void RealTimePacer::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  stopped_changed_.notify_all();
}

LockstepPacer::LockstepPacer(LockstepOptions options, std::chrono::nanoseconds period,
                             std::string who, runtime::StatusCounter& timeouts,
                             runtime::EventLog& events)
    : options_(std::move(options)),
      who_(std::move(who)),
      timeouts_(timeouts),
      events_(events),
      period_(period) {
  for (const auto& name : options_.controllers) {
    answered_[name] = -1;
  }
}

void LockstepPacer::start() {
  std::lock_guard lock(mutex_);
  stopped_ = false;
  timed_ticks_ = 0;
  first_answered_ = last_answered_ = {};
  waits_.clear();
  work_.clear();
  to_written_.clear();
  delivered_.clear();
}

// The first tick after start() waits for the controllers to start: it sets
// the origin and is not timed. written_ns: the DDS source time of the tick's
// last command (system clock), 0 when unknown; called_ns and answered_ns the
// same clock's times around the wait.
void LockstepPacer::time_tick(std::chrono::steady_clock::time_point called,
                              std::chrono::steady_clock::time_point answered,
                              std::int64_t called_ns, std::int64_t answered_ns,
                              std::int64_t written_ns) {
  if (last_answered_ == std::chrono::steady_clock::time_point{}) {
    first_answered_ = answered;
  } else {
    waits_.add(answered - called);
    work_.add(called - last_answered_);
    if (written_ns > 0) {
      to_written_.add(std::chrono::nanoseconds(written_ns - called_ns));
      delivered_.add(std::chrono::nanoseconds(answered_ns - written_ns));
    }
    ++timed_ticks_;
  }
  last_answered_ = answered;
}

std::string LockstepPacer::summary() const {
  if (timed_ticks_ == 0) {
    return "";
  }
  const double simulated_s =
      std::chrono::duration<double>(period_).count() * static_cast<double>(timed_ticks_);
  const double wall_s = std::chrono::duration<double>(last_answered_ - first_answered_).count();
  const double tick_ms = 1e3 * wall_s / static_cast<double>(timed_ticks_);
  char line[128];
  std::snprintf(line, sizeof line,
                "lockstep: simulated %.3f s in %.1f s wall: %.2fx real time; per tick %.3f ms: ",
                simulated_s, wall_s, wall_s > 0.0 ? simulated_s / wall_s : 0.0, tick_ms);
  std::string text = std::string(line) + "waiting for the controllers' commands " +
                     waits_.mean_and_p99() + ", the robot's own work " + work_.mean_and_p99();
  if (to_written_.count() > 0) {
    text += "; the wait: sensors out to the last command written " + to_written_.mean_and_p99() +
            ", its delivery to the robot " + delivered_.mean_and_p99();
  }
  return text;
}

// On a DDS thread, after the actuator side staged the command.
// A command with no tick (msg::kNoTick: a mode switch before the controller's
// first reference) answers nothing; the actuator side applied it all the same.
void LockstepPacer::observe(const wbi::msg::ActuatorCommand& command, std::int64_t written_ns) {
  if (command.tick() == wbi::msg::kNoTick) {
    return;
  }
  {
    std::lock_guard lock(mutex_);
    const auto sender = answered_.find(command.controller().to_string());
    if (sender == answered_.end()) {
      return;  // a controller the simulation does not wait for
    }
    const auto tick = static_cast<std::int64_t>(command.tick());
    sender->second = std::max(sender->second, tick);
    // The tick's last command written: the one the wait ends on.
    if (tick > written_tick_) {
      written_tick_ = tick;
      written_ns_ = written_ns;
    } else if (tick == written_tick_) {
      written_ns_ = std::max(written_ns_, written_ns);
    }
  }
  changed_.notify_all();
}

bool LockstepPacer::all_answered(std::uint64_t tick) const {
  return std::all_of(answered_.begin(), answered_.end(), [&](const auto& controller) {
    return controller.second >= static_cast<std::int64_t>(tick);
  });
}

void LockstepPacer::wait(std::uint64_t tick) {
  const auto called = std::chrono::steady_clock::now();
  const std::int64_t called_ns = dds::source_clock_now_ns();
  std::unique_lock lock(mutex_);
  // The first tick waits for the controllers to start; later ticks for one control step.
  const double timeout_s = tick == 0 ? options_.start_timeout_s : options_.timeout_s;
  if (!changed_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                         [&] { return stopped_ || all_answered(tick); })) {
    timeouts_.add();
    std::ostringstream line;
    line << who_ << ": tick " << tick << " not answered by every controller within " << timeout_s
         << " s: stepping on";
    const std::string text = line.str();
    runtime::print_line(stderr, text);
    events_.emit(EventSeverity::warning, EventKind::loop_stall, text);
  }
  if (!stopped_) {  // the ticks stepped while stopping are not the run's
    const bool written = written_tick_ == static_cast<std::int64_t>(tick);
    time_tick(called, std::chrono::steady_clock::now(), called_ns, dds::source_clock_now_ns(),
              written ? written_ns_ : 0);
  }
}

void LockstepPacer::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
}

}  // namespace wbi::robot
