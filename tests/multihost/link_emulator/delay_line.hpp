// One direction of an emulated link: Ethernet frames go in, and come out
// after a one-way delay drawn uniformly from [delay - jitter, delay + jitter],
// or never (independent loss with a fixed probability) — what `tc netem delay
// D J loss P` does, for kernels without sch_netem. Unlike netem, frames never
// overtake each other: a frame leaves no earlier than the one before it, as on
// a real switched path where jitter is queueing.
//
// The frames wait in a ring of preallocated slots: offer() and release()
// allocate nothing. A full ring drops the frame (counted), like netem's limit.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace wbi::link_emulator {

struct Impairment {
  std::int64_t delay_ns = 0;
  std::int64_t jitter_ns = 0;   // delay is uniform in [delay - jitter, delay + jitter], at least 0
  double loss_probability = 0;  // per frame, independent
};

struct LineCounters {
  std::uint64_t forwarded = 0;
  std::uint64_t lost = 0;      // dropped on purpose (the loss probability)
  std::uint64_t overflow = 0;  // dropped because the ring was full
  std::uint64_t oversize = 0;  // dropped because larger than a slot
};

class DelayLine {
 public:
  static constexpr std::size_t kMaxFrameBytes = 2048;  // an MTU of 1500 plus headers fits

  // Throws std::invalid_argument naming the bad field (negative delay or
  // jitter, loss outside [0, 1], no slots).
  DelayLine(const Impairment& impairment, std::size_t slots, std::uint64_t seed);

  // A frame that arrived at now_ns: queued with its departure time, or dropped.
  void offer(std::span<const std::uint8_t> frame, std::int64_t now_ns);

  // Hands every frame due at now_ns, oldest first, to send(std::span<const std::uint8_t>).
  template <typename Send>
  void release(std::int64_t now_ns, Send&& send) {
    while (count_ > 0 && slots_[head_].due_ns <= now_ns) {
      const Slot& slot = slots_[head_];
      send(std::span<const std::uint8_t>(slot.bytes.data(), slot.size));
      ++counters_.forwarded;
      head_ = (head_ + 1) % slots_.size();
      --count_;
    }
  }

  // Departure time of the oldest queued frame; -1 when the line is empty.
  std::int64_t next_due_ns() const { return count_ > 0 ? slots_[head_].due_ns : -1; }
  std::size_t queued() const { return count_; }
  const LineCounters& counters() const { return counters_; }

 private:
  struct Slot {
    std::int64_t due_ns = 0;
    std::size_t size = 0;
    std::array<std::uint8_t, kMaxFrameBytes> bytes{};
  };

  Impairment impairment_;
  std::vector<Slot> slots_;
  std::size_t head_ = 0;   // oldest queued frame
  std::size_t count_ = 0;  // frames queued
  std::int64_t last_due_ns_ = 0;
  std::mt19937_64 random_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  LineCounters counters_;
};

}  // namespace wbi::link_emulator
