// The bounded queue between the DDS callbacks (producers, any thread) and the
// recorder's writer thread (the one consumer). Slots are preallocated and
// their byte buffers keep their capacity, so a steady stream allocates
// nothing. A full queue drops the sample and counts it: never silently.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

namespace wbi::recording {

struct QueuedSample {
  std::uint32_t source = 0;  // the producer's index (the recorder's subscription)
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::vector<std::uint8_t> bytes;
};

class SampleQueue {
 public:
  explicit SampleQueue(std::size_t capacity);

  // Copies the sample in; false (and counted in dropped()) when the queue is full.
  bool push(std::uint32_t source, std::uint64_t log_time, std::uint64_t publish_time,
            std::span<const std::uint8_t> bytes);

  // Waits up to `timeout` for samples, then hands each queued one to `consume`
  // in arrival order, outside the lock (producers keep pushing meanwhile).
  // Returns how many were consumed. One consumer thread only.
  template <class Consume>
  std::size_t drain(Consume&& consume, std::chrono::nanoseconds timeout) {
    std::uint64_t end = 0;
    {
      std::unique_lock lock(mutex_);
      not_empty_.wait_for(lock, timeout, [&] { return head_ != tail_ || wake_; });
      wake_ = false;
      end = head_;
    }
    const std::uint64_t begin = tail_;  // only this thread moves tail_
    for (std::uint64_t i = begin; i < end; ++i) {
      consume(static_cast<const QueuedSample&>(slots_[i % slots_.size()]));
    }
    std::lock_guard lock(mutex_);
    tail_ = end;
    return static_cast<std::size_t>(end - begin);
  }

  // Ends the consumer's current wait early.
  void wake();

  std::uint64_t dropped() const;
  std::size_t capacity() const { return slots_.size(); }
  // Largest number of samples that were waiting at once.
  std::size_t high_water() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable not_empty_;
  std::vector<QueuedSample> slots_;
  std::uint64_t head_ = 0;  // next slot to fill (monotonic)
  std::uint64_t tail_ = 0;  // next slot to consume (monotonic)
  std::uint64_t dropped_ = 0;
  std::size_t high_water_ = 0;
  bool wake_ = false;
};

}  // namespace wbi::recording
