#include "wbi/runtime/clock.hpp"

#include <algorithm>
#include <chrono>

#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

namespace wbi::runtime {

std::int64_t SystemClock::now_ns() const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

bool SystemClock::sleep_until(std::int64_t time_ns) {
  const std::chrono::system_clock::time_point until{
      std::chrono::duration_cast<std::chrono::system_clock::duration>(
          std::chrono::nanoseconds(time_ns))};
  std::unique_lock lock(mutex_);
  const std::uint64_t seen = wakes_;
  woken_.wait_until(lock, until, [&] { return wakes_ != seen; });
  return wakes_ == seen && now_ns() >= time_ns;
}

void SystemClock::wake() {
  {
    std::lock_guard lock(mutex_);
    ++wakes_;
  }
  woken_.notify_all();
}

std::int64_t SteppedClock::now_ns() const {
  std::lock_guard lock(mutex_);
  return now_ns_;
}

bool SteppedClock::sleep_until(std::int64_t time_ns) {
  std::unique_lock lock(mutex_);
  const std::uint64_t seen = wakes_;
  changed_.wait(lock, [&] { return now_ns_ >= time_ns || wakes_ != seen; });
  return now_ns_ >= time_ns;
}

void SteppedClock::wake() {
  {
    std::lock_guard lock(mutex_);
    ++wakes_;
  }
  changed_.notify_all();
}

void SteppedClock::set_ns(std::int64_t time_ns) {
  {
    std::lock_guard lock(mutex_);
    now_ns_ = std::max(now_ns_, time_ns);
  }
  changed_.notify_all();
}

void SteppedClock::advance_ns(std::int64_t step_ns) {
  {
    std::lock_guard lock(mutex_);
    now_ns_ += std::max<std::int64_t>(step_ns, 0);
  }
  changed_.notify_all();
}

struct SimulationClock::Impl {
  dds::Subscriber<msg::SimulationClock> subscriber;
  Impl(dds::Participant& participant, SimulationClock& clock)
      : subscriber(participant, dds::topics::kClock, dds::qos::kStream,
                   [&clock](const msg::SimulationClock& sample, const dds::detail::SampleInfo&) {
                     clock.set_ns(sample.time_ns());
                   }) {}
};

SimulationClock::SimulationClock(dds::Participant& participant)
    : SteppedClock(0), impl_(std::make_unique<Impl>(participant, *this)) {}

SimulationClock::~SimulationClock() = default;

}  // namespace wbi::runtime
