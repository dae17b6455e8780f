// Subscriber<T>: the newest sample of a topic, with its stamp and age, an
// optional callback per sample, and a blocking wait with timeout.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "detail/endpoints.hpp"
#include "message_traits.hpp"
#include "participant.hpp"
#include "producers.hpp"

namespace wbi::dds {

template <class T>
struct Received {
  T sample;
  std::int64_t source_stamp_ns = 0;  // DDS source timestamp
  std::int64_t received_ns = 0;      // steady clock at arrival (detail::steady_now_ns)
  std::uint64_t count = 0;           // samples received so far, this one included

  // Seconds since arrival.
  double age_s() const { return 1e-9 * static_cast<double>(detail::steady_now_ns() - received_ns); }
};

template <Message T>
class Subscriber : private detail::ReaderSink {
 public:
  // Called on a DDS thread for every sample, once it is the latest.
  using Callback = std::function<void(const T& sample, const detail::SampleInfo& info)>;

  // producers: ProducerPolicy::one() for a robot's stream, so that a second
  // writer of the topic is dropped, not mixed in (see producers.hpp).
  Subscriber(Participant& participant, const std::string& topic, const std::string& qos_profile,
             Callback callback = nullptr, ProducerPolicy producers = {})
      : callback_(std::move(callback)),
        reader_(participant, topic, new typename MessageTraits<T>::TypeSupport(), qos_profile,
                *this, {}, std::move(producers)) {}

  ~Subscriber() override = default;
  Subscriber(const Subscriber&) = delete;
  Subscriber& operator=(const Subscriber&) = delete;

  // The newest sample, if any arrived.
  std::optional<Received<T>> latest() const {
    std::lock_guard lock(mutex_);
    if (latest_.count == 0) {
      return std::nullopt;
    }
    return latest_;
  }

  // Copies the newest sample into out without allocating once out has grown to
  // size. Returns false when none arrived yet.
  bool latest_into(Received<T>& out) const {
    std::lock_guard lock(mutex_);
    if (latest_.count == 0) {
      return false;
    }
    out = latest_;
    return true;
  }

  // Waits until a sample newer than the `after`-th arrives (after = 0: any
  // sample) and copies it into out. Returns false on timeout.
  bool wait_newer(Received<T>& out, std::uint64_t after, std::chrono::nanoseconds timeout) const {
    std::unique_lock lock(mutex_);
    if (!arrived_.wait_for(lock, timeout, [&] { return latest_.count > after; })) {
      return false;
    }
    out = latest_;
    return true;
  }

  // Calls read(received) with the newest sample in place, under the
  // subscriber's lock: nothing is copied but what `read` copies into its own
  // buffers, and the next sample waits until it returns (keep it short). An
  // exception from `read` propagates. Returns false when none arrived yet.
  template <class Read>
  bool read_latest(Read&& read) const {
    std::lock_guard lock(mutex_);
    if (latest_.count == 0) {
      return false;
    }
    std::forward<Read>(read)(std::as_const(latest_));
    return true;
  }

  // Waits until a sample newer than the `after`-th arrives, then reads it as
  // read_latest does. Returns false on timeout.
  template <class Read>
  bool read_newer(std::uint64_t after, std::chrono::nanoseconds timeout, Read&& read) const {
    std::unique_lock lock(mutex_);
    if (!arrived_.wait_for(lock, timeout, [&] { return latest_.count > after; })) {
      return false;
    }
    std::forward<Read>(read)(std::as_const(latest_));
    return true;
  }

  std::uint64_t count() const {
    std::lock_guard lock(mutex_);
    return latest_.count;
  }

  // Replaces the callback (nullptr: none). Waits for a call in progress, so
  // that no call of the old one follows; never call it from the callback.
  void set_callback(Callback callback) {
    std::lock_guard lock(callback_mutex_);
    callback_ = std::move(callback);
  }

  int matched() const { return reader_.matched(); }
  detail::Guid guid() const { return reader_.guid(); }
  // With ProducerPolicy::one: the writer taken and what was dropped.
  ProducerCounts producers() const { return reader_.producers(); }
  // How many times a writer of the topic was found that this subscriber cannot
  // match (e.g. best effort, while its profile is reliable); the first is also
  // said on stderr. Fast DDS reports a writer again when its discovery data is
  // processed again (a CI run counted 2 for one writer): 0 means none, not a count
  // of writers.
  int incompatible_writers() const { return reader_.incompatible_writers(); }
  bool wait_for_publishers(int count, std::chrono::nanoseconds timeout) const {
    return reader_.wait_matched(count, timeout);
  }
  const std::string& topic() const { return reader_.topic(); }

 private:
  void* storage() override { return &incoming_; }

  void on_sample(const detail::SampleInfo& info) override {
    {
      std::lock_guard lock(mutex_);
      latest_.sample = incoming_;  // reuses the capacity of latest_'s sequences
      latest_.source_stamp_ns = info.source_stamp_ns;
      latest_.received_ns = info.received_ns;
      ++latest_.count;
    }
    arrived_.notify_all();
    std::lock_guard lock(callback_mutex_);
    if (callback_) {
      callback_(incoming_, info);
    }
  }

  // Held while the callback runs (set_callback). Recursive: in one process
  // Fast DDS delivers on the writer's thread, so a callback's own writes can
  // bring this reader a sample before it returns.
  std::recursive_mutex callback_mutex_;
  Callback callback_;
  T incoming_;  // written only on the DDS thread that takes samples
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  Received<T> latest_;
  detail::Reader reader_;  // last: destroyed first, so no callback outlives the members above
};

// An owner for ProducerPolicy::owned_by: the writer that `description` (a
// bound reader of a robot's description) took; before its first sample, the
// description's writer as discovery knows it (the robot holding the name), so
// that a robot's first sensor samples, which can come before its latched
// description, are taken and a rogue's are not. Both must outlive the readers
// that call it.
template <Message Description>
std::function<detail::Guid()> description_owner(const Participant& participant,
                                                const Subscriber<Description>& description) {
  return [&participant, &description] {
    const auto bound = description.producers().bound;
    return bound != detail::Guid{} ? bound : participant.oldest_writer_of(description.topic());
  };
}

}  // namespace wbi::dds
