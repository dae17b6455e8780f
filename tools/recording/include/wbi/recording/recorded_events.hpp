// The events (wbi/events, idl/events.idl) a recording holds, decoded: what
// `wbi bag info` lists and what a windowed recorder's file was written for.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <wbi/mcap/reader.hpp>
#include <wbi/vocabulary/event.hpp>

namespace wbi::recording {

struct RecordedEvent {
  std::uint64_t log_time = 0;  // when the recorder received it [ns, system time]
  std::int64_t stamp_ns = 0;   // Header.stamp_ns: when it happened (system time of its sender)
  EventSeverity severity = EventSeverity::info;
  EventKind kind = EventKind::lifecycle;
  std::string robot;
  std::string participant;
  std::string source;
  std::string subject;
  std::string text;
  std::uint32_t suppressed = 0;
};

struct RecordedEvents {
  std::vector<RecordedEvent> events;  // in log-time order
  // Messages of the channel that did not decode (another type, a cut sample,
  // a severity or kind this build does not know): counted, not listed.
  std::size_t undecoded = 0;
};

// Reads every message of the wbi/events channel (a pass over the whole file
// when it has one); nothing when it has none.
RecordedEvents read_events(const mcap::Reader& reader);

}  // namespace wbi::recording
