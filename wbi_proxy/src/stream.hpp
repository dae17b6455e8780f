// One robot stream as the proxy reads it: the subscriber, a copy of its newest
// sample, and for blocking reads the count of samples seen at the last read of
// each kind (so that each kind waits for a sample newer than its own last one).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/producers.hpp>
#include <wbi/dds/subscriber.hpp>

#include "wbi/types.hpp"

namespace wbi::proxy {

inline std::string seconds_text(double s) { return std::to_string(s) + " s"; }

template <class T, std::size_t Kinds>
struct Stream {
  dds::Subscriber<T> subscriber;
  dds::Received<T> received;
  std::array<std::uint64_t, Kinds> seen{};
  std::string what;  // e.g. "sensor samples of robot 'arm' on wbi/arm/sensors"
  // The sample init() waited for (its count) and the kinds that have not read
  // since: the first read of each kind takes that sample whatever its age.
  // In lockstep the robot waits for the answer to it however long the start
  // took after it arrived (a secured start's handshakes, a remote model's
  // first calls: over max_age_s in some runs, and the run never began); a
  // running robot has sent newer samples by then, whose age counts as usual.
  std::uint64_t init_count = 0;
  std::array<bool, Kinds> init_sample_unread{};

  Stream(dds::Participant& participant, const std::string& topic, const char* profile,
         std::string description, dds::ProducerPolicy producers)
      : subscriber(participant, topic, profile, nullptr, std::move(producers)),
        what(std::move(description)) {}

  // Brings `received` up to date for a read of `kind`; throws when there is no
  // usable sample (TimeoutError for a blocking read, StaleDataError else).
  const T& take(std::size_t kind, ReadMode mode, double max_age_s,
                std::chrono::milliseconds timeout) {
    if (mode == ReadMode::blocking) {
      if (!subscriber.wait_newer(received, seen[kind], timeout)) {
        throw TimeoutError("no new " + what + " within " +
                           seconds_text(std::chrono::duration<double>(timeout).count()));
      }
    } else if (!subscriber.latest_into(received)) {
      throw StaleDataError("no " + what + " received");
    }
    seen[kind] = received.count;
    const bool init_sample =
        std::exchange(init_sample_unread[kind], false) && received.count == init_count;
    const double age = received.age_s();
    if (age > max_age_s && !init_sample) {
      throw StaleDataError(what + ": newest is " + seconds_text(age) + " old (limit " +
                           seconds_text(max_age_s) + ")");
    }
    return received.sample;
  }

  // Called at the end of init(): the newest sample is the one it waited for.
  void mark_init_sample() {
    init_count = received.count;
    init_sample_unread.fill(received.count > 0);
    seen.fill(received.count > 0 ? received.count - 1 : 0);
  }

  Stamp stamp() const {
    return {received.sample.header().stamp_ns(), received.sample.header().seq(), received.age_s()};
  }
};

}  // namespace wbi::proxy
