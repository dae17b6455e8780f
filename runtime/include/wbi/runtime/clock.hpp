// Clocks for component loops: the time a loop runs on, and a way to sleep
// until a given time on it.
//   SystemClock      wall-clock time (ns since the Unix epoch), the default;
//   SteppedClock     time that moves only when told (tests, lockstep runs);
//   SimulationClock  a SteppedClock driven by the simulation's wbi/clock topic.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>

namespace wbi::dds {
class Participant;
}

namespace wbi::runtime {

class Clock {
 public:
  virtual ~Clock() = default;
  // Now on this clock [ns].
  virtual std::int64_t now_ns() const = 0;
  // Blocks until now_ns() >= time_ns; returns false when wake() (or a
  // spurious wake-up) ended the sleep early.
  virtual bool sleep_until(std::int64_t time_ns) = 0;
  // Ends every sleep_until in progress (used to stop loops).
  virtual void wake() = 0;
  virtual const char* name() const = 0;
};

class SystemClock final : public Clock {
 public:
  std::int64_t now_ns() const override;
  bool sleep_until(std::int64_t time_ns) override;
  void wake() override;
  const char* name() const override { return "system"; }

 private:
  std::mutex mutex_;
  std::condition_variable woken_;
  std::uint64_t wakes_ = 0;
};

class SteppedClock : public Clock {
 public:
  explicit SteppedClock(std::int64_t start_ns = 0) : now_ns_(start_ns) {}
  std::int64_t now_ns() const override;
  bool sleep_until(std::int64_t time_ns) override;
  void wake() override;
  const char* name() const override { return "stepped"; }

  // Moves time to time_ns (never backwards) and wakes the sleepers it reaches.
  void set_ns(std::int64_t time_ns);
  void advance_ns(std::int64_t step_ns);

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::int64_t now_ns_;
  std::uint64_t wakes_ = 0;
};

// Simulated time from wbi/clock (SimulationClock samples): now_ns() is the
// newest sample's time, 0 before the first.
class SimulationClock final : public SteppedClock {
 public:
  explicit SimulationClock(dds::Participant& participant);
  ~SimulationClock() override;
  const char* name() const override { return "simulation"; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::runtime
