// EventLog: the events one source (a component, the launcher) has to tell,
// queued for the thread that publishes them on wbi/events (EventPump).
//
//   any thread:  events().emit(EventSeverity::warning, EventKind::watchdog_trip,
//                              "joint 'j1' got no command for 0.1 s", "j1");
//
// emit() never blocks and never allocates: texts are copied (truncated) into a
// fixed ring of kCapacity records, a lock-free bounded queue (D. Vyukov's
// bounded MPMC queue: one sequence number per slot). It is also rate-limited
// per kind, as a token bucket of `burst` events refilled at `per_second` (in
// its GCRA form: one atomic "theoretical arrival time" per kind). An event
// refused by the limit, or by a full queue, is counted; the next event of that
// kind that goes out carries the count (Event.suppressed), so none is lost
// silently.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <wbi/vocabulary/event.hpp>

namespace wbi::runtime {

// One queued event. Strings are null-terminated and truncated to fit.
struct EventRecord {
  static constexpr std::size_t kMaxName = 64;   // msg::BoundedName
  static constexpr std::size_t kMaxText = 256;  // msg::Event.subject and .text

  std::int64_t stamp_ns = 0;  // system time
  EventSeverity severity = EventSeverity::info;
  EventKind kind = EventKind::lifecycle;
  std::uint32_t suppressed = 0;
  std::array<char, kMaxName + 1> robot{};   // empty: the log's default robot
  std::array<char, kMaxName + 1> source{};  // empty: the publisher's source
  std::array<char, kMaxText + 1> subject{};
  std::array<char, kMaxText + 1> text{};
};

struct EventRateLimit {
  double per_second = 2.0;  // sustained events per second and kind
  double burst = 10.0;      // events of one kind that may go out at once
};

class EventLog {
 public:
  static constexpr std::size_t kCapacity = 128;  // a power of two

  explicit EventLog(EventRateLimit limit = {});
  EventLog(const EventLog&) = delete;
  EventLog& operator=(const EventLog&) = delete;

  // Queues an event, stamped now; false when the rate limit or a full queue
  // refused it (then counted). Any thread; never blocks or allocates.
  // `source` names what the event is about when it is not the log's owner
  // (the launcher's events are about the processes it runs).
  bool emit(EventSeverity severity, EventKind kind, std::string_view text,
            std::string_view subject = {}, std::string_view robot = {},
            std::string_view source = {});

  // The oldest queued event, if any (one consumer thread).
  bool pop(EventRecord& out);

  // The robot named by events that name none (set before the events flow,
  // e.g. in on_configure).
  void set_default_robot(std::string_view robot);
  const char* default_robot() const { return default_robot_.data(); }

  std::uint64_t emitted() const { return emitted_.load(std::memory_order_relaxed); }
  std::uint64_t rate_limited() const { return rate_limited_.load(std::memory_order_relaxed); }
  std::uint64_t overflowed() const { return overflowed_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::size_t kKinds = enum_count<EventKind>();
  struct Slot {
    std::atomic<std::size_t> sequence{0};
    EventRecord record;
  };

  bool admit(std::size_t kind, std::int64_t now_ns);

  std::int64_t interval_ns_;                                     // 1 / per_second
  std::int64_t tolerance_ns_;                                    // (burst − 1) intervals
  std::array<std::atomic<std::int64_t>, kKinds> next_due_ns_{};  // GCRA's theoretical arrival time
  std::array<std::atomic<std::uint32_t>, kKinds> suppressed_{};

  std::array<Slot, kCapacity> slots_;
  alignas(64) std::atomic<std::size_t> enqueue_at_{0};
  alignas(64) std::atomic<std::size_t> dequeue_at_{0};

  std::array<char, EventRecord::kMaxName + 1> default_robot_{};
  std::atomic<std::uint64_t> emitted_{0};
  std::atomic<std::uint64_t> rate_limited_{0};
  std::atomic<std::uint64_t> overflowed_{0};
};

}  // namespace wbi::runtime
