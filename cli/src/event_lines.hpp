// Events of wbi/events (idl/events.idl) as `wbi events` prints them, and the
// filter it applies: one human line, or one JSON object per line.
//
//   23:41:02.123 WARNING robot:arm  WATCHDOG_TRIP  arm  [joint_1,joint_2] 2 joint(s) … (+3
//   suppressed)
//   {"stamp_ns":…,"time":"23:41:02.123","robot":"arm","participant":"robot","source":"arm",…}
#pragma once

#include <bitset>
#include <optional>
#include <string>
#include <string_view>

#include <wbi/msg/events.h>
#include <wbi/vocabulary/event.hpp>

namespace wbi::cli {

struct EventFilter {
  std::optional<std::string> robot;                                 // header.robot, exactly
  EventSeverity min_severity = EventSeverity::debug;                // this one and worse
  std::bitset<enum_count<EventKind>()> kinds = ~decltype(kinds){};  // all by default

  bool matches(const msg::Event& event) const;
};

// "WATCHDOG_TRIP,claim_forced" → those kinds (any case). Throws UsageError
// naming an unknown or empty one, with the known ones.
std::bitset<enum_count<EventKind>()> parse_event_kinds(std::string_view list);
// "warning" → warning (any case). Throws UsageError naming an unknown one.
EventSeverity parse_event_severity(std::string_view name);

// The stamp (system time, ns) as local "HH:MM:SS.mmm".
std::string clock_time(std::int64_t stamp_ns);
// One line, without its newline.
std::string human_line(const msg::Event& event);
// One JSON object, without its newline (invalid UTF-8 from the wire replaced).
std::string json_line(const msg::Event& event);

}  // namespace wbi::cli
