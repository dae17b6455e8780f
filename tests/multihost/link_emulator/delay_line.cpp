#include "delay_line.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace wbi::link_emulator {

DelayLine::DelayLine(const Impairment& impairment, std::size_t slots, std::uint64_t seed)
    : impairment_(impairment), random_(seed) {
  if (impairment.delay_ns < 0) {
    throw std::invalid_argument("delay must be >= 0, got " + std::to_string(impairment.delay_ns) +
                                " ns");
  }
  if (impairment.jitter_ns < 0) {
    throw std::invalid_argument("jitter must be >= 0, got " + std::to_string(impairment.jitter_ns) +
                                " ns");
  }
  if (!(impairment.loss_probability >= 0.0 && impairment.loss_probability <= 1.0)) {
    throw std::invalid_argument("loss probability must be in [0, 1], got " +
                                std::to_string(impairment.loss_probability));
  }
  if (slots == 0) {
    throw std::invalid_argument("the queue needs at least one slot");
  }
  slots_.resize(slots);
}

void DelayLine::offer(std::span<const std::uint8_t> frame, std::int64_t now_ns) {
  if (frame.size() > kMaxFrameBytes) {
    ++counters_.oversize;
    return;
  }
  if (impairment_.loss_probability > 0.0 && unit_(random_) < impairment_.loss_probability) {
    ++counters_.lost;
    return;
  }
  if (count_ == slots_.size()) {
    ++counters_.overflow;
    return;
  }
  std::int64_t delay_ns = impairment_.delay_ns;
  if (impairment_.jitter_ns > 0) {
    const double offset = (2.0 * unit_(random_) - 1.0) * static_cast<double>(impairment_.jitter_ns);
    delay_ns = std::max<std::int64_t>(0, delay_ns + static_cast<std::int64_t>(offset));
  }
  // No overtaking: a frame leaves no earlier than the one queued before it.
  const std::int64_t due_ns = std::max(now_ns + delay_ns, count_ > 0 ? last_due_ns_ : now_ns);
  Slot& slot = slots_[(head_ + count_) % slots_.size()];
  slot.due_ns = due_ns;
  slot.size = frame.size();
  std::memcpy(slot.bytes.data(), frame.data(), frame.size());
  last_due_ns_ = due_ns;
  ++count_;
}

}  // namespace wbi::link_emulator
