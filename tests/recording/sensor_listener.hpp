// A subscriber in the test process to the talker's pattern sensor samples
// (tests/dds/sample_pattern.hpp), keeping what the record/play tests check.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <wbi/dds/subscriber.hpp>

#include "sample_pattern.hpp"

namespace wbi::test {

// What a subscriber in this process received: sequence numbers, arrival times
// and the first sample that broke the talker's pattern.
class SensorListener {
 public:
  SensorListener(wbi::dds::Participant& participant, const std::string& robot,
                 const std::string& topic)
      : subscriber_(participant, topic, wbi::dds::qos::kStream,
                    [this, robot](const wbi::msg::SensorSample& sample,
                                  const wbi::dds::detail::SampleInfo& info) {
                      std::lock_guard lock(mutex_);
                      seqs_.push_back(sample.header().seq());
                      arrivals_ns_.push_back(info.received_ns);
                      if (mismatch_.empty()) {
                        mismatch_ = pattern_mismatch(sample, robot);
                      }
                    }) {}

  // Waits until `count` samples arrived; false on timeout.
  bool wait_for(std::size_t count, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (received() >= count) {
        return true;
      }
      wbi::dds::Received<wbi::msg::SensorSample> latest;
      subscriber_.wait_newer(latest, subscriber_.count(),
                             std::chrono::milliseconds(100));  // wakes on the next sample
    }
    return received() >= count;
  }
  std::size_t received() const {
    std::lock_guard lock(mutex_);
    return seqs_.size();
  }
  std::vector<std::uint64_t> seqs() const {
    std::lock_guard lock(mutex_);
    return seqs_;
  }
  std::vector<std::int64_t> arrivals_ns() const {
    std::lock_guard lock(mutex_);
    return arrivals_ns_;
  }
  std::string mismatch() const {
    std::lock_guard lock(mutex_);
    return mismatch_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::uint64_t> seqs_;
  std::vector<std::int64_t> arrivals_ns_;
  std::string mismatch_;
  wbi::dds::Subscriber<wbi::msg::SensorSample> subscriber_;
};

// first, first + 1, ..., first + count - 1: what a player of pattern samples should deliver.
inline std::vector<std::uint64_t> consecutive_seqs(std::uint64_t first, std::uint64_t count) {
  std::vector<std::uint64_t> seqs(count);
  for (std::uint64_t i = 0; i < count; ++i) {
    seqs[i] = first + i;
  }
  return seqs;
}

}  // namespace wbi::test
