// StatusReport: what a component tells the world about itself beyond its
// lifecycle and loop timing — named event counters (rejected commands,
// watchdog trips, dropped samples…) and its last error. Every Component has
// one (Component::report()); the ComponentRunner copies it into
// msg::ComponentStatus (counters, last_error) at its status rate.
//
//   on_configure:  rejected_ = &report().counter("rejected_commands");
//   any thread:    rejected_->add();  report().set_error("command from 'pd' rejected: …");
//
// Counters are registered in on_configure (allocates the name, at most
// kMaxCounters; registering a name again returns the same counter, so a
// configure after a cleanup keeps counting). After that, add/set and
// set_error never allocate and may be called from any thread (DDS callbacks,
// the loop): counters are atomics, the error text is copied into a fixed
// buffer under a short lock.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>

namespace wbi::runtime {

class StatusCounter {
 public:
  void add(std::uint64_t n = 1) { value_.fetch_add(n, std::memory_order_relaxed); }
  void set(std::uint64_t value) { value_.store(value, std::memory_order_relaxed); }
  std::uint64_t value() const { return value_.load(std::memory_order_relaxed); }

 private:
  std::atomic<std::uint64_t> value_{0};
};

class StatusReport {
 public:
  static constexpr std::size_t kMaxCounters = 16;      // ComponentStatus.counters' bound
  static constexpr std::size_t kMaxErrorLength = 512;  // ComponentStatus.last_error's bound

  // The counter named `name`, created at 0 on first use. Throws
  // std::invalid_argument for an empty name or when kMaxCounters are in use.
  StatusCounter& counter(std::string_view name);

  std::size_t counter_count() const { return count_.load(std::memory_order_acquire); }
  const std::string& counter_name(std::size_t i) const { return entries_[i].name; }
  std::uint64_t counter_value(std::size_t i) const { return entries_[i].counter.value(); }

  // Replaces the last error (truncated to kMaxErrorLength characters); empty clears it.
  void set_error(std::string_view text);
  // Copies the last error into `out`: a std::string (reuses its capacity) or the
  // message's bounded string (anything assignable from a C string).
  template <class String>
  void last_error_into(String& out) const {
    std::lock_guard lock(error_mutex_);
    out = error_.data();
  }
  std::string last_error() const;
  // Incremented by every set_error: tells a reader that the error changed.
  std::uint64_t error_count() const { return errors_.load(std::memory_order_acquire); }

 private:
  struct Entry {
    std::string name;  // written once, before count_ is published
    StatusCounter counter;
  };
  std::mutex registration_;  // counter() only
  std::array<Entry, kMaxCounters> entries_;
  std::atomic<std::size_t> count_{0};

  mutable std::mutex error_mutex_;
  std::array<char, kMaxErrorLength + 1> error_{};  // null-terminated
  std::atomic<std::uint64_t> errors_{0};
};

}  // namespace wbi::runtime
