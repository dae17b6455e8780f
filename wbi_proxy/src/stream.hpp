// One robot stream as the proxy reads it: the subscriber, a copy of its newest
// sample, and for blocking reads the count of samples seen at the last read of
// each kind (so that each kind waits for a sample newer than its own last one).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>

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
    const double age = received.age_s();
    if (age > max_age_s) {
      throw StaleDataError(what + ": newest is " + seconds_text(age) + " old (limit " +
                           seconds_text(max_age_s) + ")");
    }
    return received.sample;
  }

  // The next blocking read of every kind returns the newest sample, the one
  // received already included (RobotConnection::wait says why).
  void rewind_reads() { seen.fill(received.count > 0 ? received.count - 1 : 0); }

  Stamp stamp() const {
    return {received.sample.header().stamp_ns(), received.sample.header().seq(), received.age_s()};
  }
};

}  // namespace wbi::proxy
