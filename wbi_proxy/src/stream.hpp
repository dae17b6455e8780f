// One robot stream as the proxy reads it: the subscriber, which holds the
// newest sample (the proxy keeps no copy of it: each read converts from it into
// the caller's buffers), the header of the sample read last, and for blocking
// reads the count of samples seen at the last read of each kind (so that each
// kind waits for a sample newer than its own last one).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/producers.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/vocabulary/seconds_text.hpp>

#include "wbi/types.hpp"

namespace wbi::proxy {

// The sample read last: its header, and when it arrived.
struct LastRead {
  std::uint64_t count = 0;  // samples received up to it (0: none read yet)
  std::int64_t stamp_ns = 0;
  std::uint64_t seq = 0;
  std::int64_t received_ns = 0;
};

template <class T, std::size_t Kinds>
struct Stream {
  dds::Subscriber<T> subscriber;
  LastRead last;
  std::array<std::uint64_t, Kinds> seen{};
  std::string what;  // e.g. "sensor samples of robot 'arm' on wbi/arm/sensors"
  // A lockstep robot's sample init() waited for (its count), until a command
  // answered it: until then a read takes it whatever its age. The robot waits
  // for that answer however long the start took after the sample arrived (a
  // secured start's handshakes, the claim, a remote model's first calls in
  // the controller's configure: over max_age_s in some runs, and the run
  // never began). A robot that is not in lockstep gets no such leave.
  std::uint64_t init_count = 0;
  bool init_sample_unanswered = false;

  Stream(dds::Participant& participant, const std::string& topic, const char* profile,
         std::string description, dds::ProducerPolicy producers)
      : subscriber(participant, topic, profile, nullptr, std::move(producers)),
        what(std::move(description)) {}

  // Calls reader(const T&) with the newest sample for a read of `kind` (a
  // newer one than that kind's last, for a blocking read), in place in the
  // subscriber (dds::Subscriber::read_latest); throws when there is no usable
  // sample (TimeoutError for a blocking read, StaleDataError else), without
  // calling `reader`.
  template <class Read>
  void read(std::size_t kind, ReadMode mode, double max_age_s, std::chrono::milliseconds timeout,
            Read&& reader) {
    double age = 0.0;
    bool init_sample = false;
    auto take = [&](const dds::Received<T>& received) {
      seen[kind] = received.count;
      remember(received);
      age = received.age_s();
      init_sample = init_sample_unanswered && received.count == init_count;
      if (age <= max_age_s || init_sample) {
        reader(received.sample);
      }
    };
    if (mode == ReadMode::blocking) {
      if (!subscriber.read_newer(seen[kind], timeout, take)) {
        throw TimeoutError("no new " + what + " within " +
                           seconds_text(std::chrono::duration<double>(timeout).count()));
      }
    } else if (!subscriber.read_latest(take)) {
      throw StaleDataError("no " + what + " received");
    }
    if (age > max_age_s && !init_sample) {
      throw StaleDataError(what + ": newest is " + seconds_text(age) + " old (limit " +
                           seconds_text(max_age_s) + ")");
    }
  }

  // Waits for the first sample and reads it (init()). Returns false on timeout.
  template <class Read>
  bool read_first(std::chrono::nanoseconds timeout, Read&& reader) {
    return subscriber.read_newer(0, timeout, [&](const dds::Received<T>& received) {
      remember(received);
      reader(received.sample);
    });
  }

  // Called at the end of init(): the newest sample is the one it waited for.
  void mark_init_sample(bool lockstep) {
    init_count = last.count;
    init_sample_unanswered = lockstep && last.count > 0;
    rewind_reads();
  }
  // A command computed from what was read has gone out (DdsActuators).
  void answered() { init_sample_unanswered = false; }

  // The next blocking read of every kind returns the newest sample, the one
  // received already included (RobotConnection::wait says why).
  void rewind_reads() { seen.fill(last.count > 0 ? last.count - 1 : 0); }

  Stamp stamp() const {
    return {last.stamp_ns, last.seq,
            1e-9 * static_cast<double>(dds::detail::steady_now_ns() - last.received_ns)};
  }

 private:
  void remember(const dds::Received<T>& received) {
    last.count = received.count;
    last.stamp_ns = received.sample.header().stamp_ns();
    last.seq = received.sample.header().seq();
    last.received_ns = received.received_ns;
  }
};

}  // namespace wbi::proxy
