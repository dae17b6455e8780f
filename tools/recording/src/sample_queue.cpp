#include "sample_queue.hpp"

#include <algorithm>
#include <stdexcept>

namespace wbi::recording {

SampleQueue::SampleQueue(std::size_t capacity) : slots_(capacity) {
  if (capacity == 0) {
    throw std::invalid_argument("recorder queue capacity must be > 0");
  }
}

bool SampleQueue::push(std::uint32_t source, std::uint64_t log_time, std::uint64_t publish_time,
                       std::span<const std::uint8_t> bytes) {
  bool was_empty = false;
  {
    std::lock_guard lock(mutex_);
    if (head_ - tail_ >= slots_.size()) {
      ++dropped_;
      return false;
    }
    // The consumer never touches slot head_ before head_ moves past it.
    auto& slot = slots_[head_ % slots_.size()];
    slot.source = source;
    slot.log_time = log_time;
    slot.publish_time = publish_time;
    slot.bytes.assign(bytes.begin(), bytes.end());
    was_empty = head_ == tail_;
    ++head_;
    high_water_ = std::max(high_water_, static_cast<std::size_t>(head_ - tail_));
  }
  if (was_empty) {  // a waiting consumer found the queue empty; a busy one drains again by itself
    not_empty_.notify_one();
  }
  return true;
}

void SampleQueue::wake() {
  {
    std::lock_guard lock(mutex_);
    wake_ = true;
  }
  not_empty_.notify_one();
}

std::uint64_t SampleQueue::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

std::size_t SampleQueue::high_water() const {
  std::lock_guard lock(mutex_);
  return high_water_;
}

}  // namespace wbi::recording
