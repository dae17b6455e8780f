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

#include "detail/endpoints.hpp"
#include "message_traits.hpp"
#include "participant.hpp"

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

  Subscriber(Participant& participant, const std::string& topic, const std::string& qos_profile,
             Callback callback = nullptr)
      : callback_(std::move(callback)),
        reader_(participant, topic, new typename MessageTraits<T>::TypeSupport(), qos_profile,
                *this) {}

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

  std::uint64_t count() const {
    std::lock_guard lock(mutex_);
    return latest_.count;
  }

  int matched() const { return reader_.matched(); }
  // Writers of the topic this subscriber cannot match (e.g. best effort, while
  // its profile is reliable); the first is also said on stderr.
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
    if (callback_) {
      callback_(incoming_, info);
    }
  }

  Callback callback_;
  T incoming_;  // written only on the DDS thread that takes samples
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  Received<T> latest_;
  detail::Reader reader_;  // last: destroyed first, so no callback outlives the members above
};

}  // namespace wbi::dds
