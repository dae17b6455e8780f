#include "wbi/runtime/event_log.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace wbi::runtime {

namespace {

static_assert((EventLog::kCapacity & (EventLog::kCapacity - 1)) == 0,
              "EventLog::kCapacity must be a power of two");

template <std::size_t N>
void copy_text(std::array<char, N>& to, std::string_view from) {
  const std::size_t n = std::min(from.size(), N - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const auto byte = static_cast<unsigned char>(from[i]);
    to[i] = byte < 0x20 || byte == 0x7f ? '?' : from[i];  // one line, no terminal escapes
  }
  to[n] = '\0';
}

std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::int64_t system_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

EventLog::EventLog(EventRateLimit limit) {
  if (!(limit.per_second > 0.0) || !std::isfinite(limit.per_second) || !(limit.burst >= 1.0) ||
      !std::isfinite(limit.burst)) {
    throw std::invalid_argument("EventLog: the rate limit needs per_second > 0 and burst >= 1");
  }
  interval_ns_ = static_cast<std::int64_t>(1e9 / limit.per_second);
  tolerance_ns_ = static_cast<std::int64_t>((limit.burst - 1.0) * 1e9 / limit.per_second);
  for (std::size_t i = 0; i < kCapacity; ++i) {
    slots_[i].sequence.store(i, std::memory_order_relaxed);
  }
}

void EventLog::set_default_robot(std::string_view robot) { copy_text(default_robot_, robot); }

// GCRA: an event is admitted when its kind's theoretical arrival time is at
// most `tolerance` ahead of now; each admitted event pushes it one interval on.
bool EventLog::admit(std::size_t kind, std::int64_t now_ns) {
  std::atomic<std::int64_t>& due = next_due_ns_[kind];
  std::int64_t seen = due.load(std::memory_order_relaxed);
  for (;;) {
    const std::int64_t from = std::max(seen, now_ns);
    if (from - now_ns > tolerance_ns_) {
      return false;
    }
    if (due.compare_exchange_weak(seen, from + interval_ns_, std::memory_order_relaxed)) {
      return true;
    }
  }
}

bool EventLog::emit(EventSeverity severity, EventKind kind, std::string_view text,
                    std::string_view subject, std::string_view robot, std::string_view source) {
  const auto k = static_cast<std::size_t>(kind);
  if (k >= kKinds) {
    return false;
  }
  if (!admit(k, steady_ns())) {
    suppressed_[k].fetch_add(1, std::memory_order_relaxed);
    rate_limited_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  std::size_t at = enqueue_at_.load(std::memory_order_relaxed);
  Slot* slot = nullptr;
  for (;;) {
    slot = &slots_[at & (kCapacity - 1)];
    const std::size_t sequence = slot->sequence.load(std::memory_order_acquire);
    const auto lag = static_cast<std::ptrdiff_t>(sequence) - static_cast<std::ptrdiff_t>(at);
    if (lag == 0) {
      if (enqueue_at_.compare_exchange_weak(at, at + 1, std::memory_order_relaxed)) {
        break;
      }
    } else if (lag < 0) {  // the consumer is a whole ring behind
      suppressed_[k].fetch_add(1, std::memory_order_relaxed);
      overflowed_.fetch_add(1, std::memory_order_relaxed);
      return false;
    } else {
      at = enqueue_at_.load(std::memory_order_relaxed);
    }
  }
  EventRecord& record = slot->record;
  record.stamp_ns = system_ns();
  record.severity = severity;
  record.kind = kind;
  record.suppressed = suppressed_[k].exchange(0, std::memory_order_relaxed);
  copy_text(record.robot, robot);
  copy_text(record.source, source);
  copy_text(record.subject, subject);
  copy_text(record.text, text);
  slot->sequence.store(at + 1, std::memory_order_release);
  emitted_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

bool EventLog::pop(EventRecord& out) {
  std::size_t at = dequeue_at_.load(std::memory_order_relaxed);
  Slot* slot = nullptr;
  for (;;) {
    slot = &slots_[at & (kCapacity - 1)];
    const std::size_t sequence = slot->sequence.load(std::memory_order_acquire);
    const auto lag = static_cast<std::ptrdiff_t>(sequence) - static_cast<std::ptrdiff_t>(at + 1);
    if (lag == 0) {
      if (dequeue_at_.compare_exchange_weak(at, at + 1, std::memory_order_relaxed)) {
        break;
      }
    } else if (lag < 0) {
      return false;  // empty
    } else {
      at = dequeue_at_.load(std::memory_order_relaxed);
    }
  }
  out = slot->record;
  slot->sequence.store(at + kCapacity, std::memory_order_release);
  return true;
}

}  // namespace wbi::runtime
