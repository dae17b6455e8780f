// One producer per stream: a reader of a robot's stream (its description,
// sensors, ground truth, state, model replies) takes the samples of one
// writer, the first it hears, and drops those of any other writer of the same
// topic — a second robot of the same name, a rogue or a replayed recording
// would otherwise be mixed into its samples.
//
// The binding moves to another writer only when the bound one is gone:
// - its process, on this host, has ended (checked when a new writer is first
//   heard: a respawned robot is taken at its first sample), or
// - DDS unmatched it (its participant left, or its lease of 5 s expired);
//   then the first writer heard after the bound one's last sample is taken.
// A writer that was publishing while the bound one still was is a second
// producer, never its successor: it stays dropped.
//
// With an owner (ProducerPolicy::owned_by), the reader instead takes the
// writer of the owner's participant: a robot's sensors follow the writer of
// its description, which holds the robot's name (components/robot), so a
// rogue that starts before the robot is dropped once the description is heard.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <utility>

#include "detail/guid.hpp"

namespace wbi::dds {

// What a bound reader tells its owner, on the DDS thread that takes samples.
struct ProducerEvent {
  enum class Kind {
    foreign_sample,  // a sample of another writer was dropped
    rebound,         // the bound writer was gone: `writer` is now taken
  };
  Kind kind = Kind::foreign_sample;
  const detail::Guid* writer = nullptr;
  // The line said on stderr (naming the writers' participants: name, host,
  // pid) for a rebind and for the first sample of each foreign writer; empty
  // for the other foreign samples.
  std::string_view text;
};

struct ProducerPolicy {
  bool one_producer = false;                           // false: every writer's samples are taken
  std::function<void(const ProducerEvent&)> on_event;  // optional
  // Optional: take the writer of the participant that `owner()` belongs to,
  // e.g. the writer bound by the robot's description reader (the robot that
  // holds the name: its sensors come from the same participant). While it
  // returns all zero (owner not heard yet), the first writer is taken
  // provisionally (start-up: the latched description can come after the
  // first sensor samples); once the owner is known, the owner's participant's.
  // Called on the DDS thread, per sample: must not allocate.
  std::function<detail::Guid()> owner;

  // Bind to one producer, the first writer heard; `on_event`, when given,
  // hears the drops and rebinds.
  static ProducerPolicy one(std::function<void(const ProducerEvent&)> on_event = nullptr) {
    return {true, std::move(on_event), nullptr};
  }
  // Bind to the writer of `owner()`'s participant.
  static ProducerPolicy owned_by(std::function<detail::Guid()> owner,
                                 std::function<void(const ProducerEvent&)> on_event = nullptr) {
    return {true, std::move(on_event), std::move(owner)};
  }
};

// A bound reader's counts so far.
struct ProducerCounts {
  detail::Guid bound{};  // all zero: no writer heard yet
  std::uint64_t foreign_samples = 0;
  std::uint32_t foreign_writers = 0;
  std::uint32_t rebinds = 0;
};

}  // namespace wbi::dds
