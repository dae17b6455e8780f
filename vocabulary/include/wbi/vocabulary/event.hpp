// What happened in a run, on one timeline (wbi/events, idl/events.idl): how
// serious an event is and its kind, from a closed list that every layer and
// the wire share (the IDL follows it value for value). Tools filter and
// trigger on these names (`wbi events --kind`, `wbi record --trigger`).
#pragma once

#include <cstdint>

#include "wbi/vocabulary/enum_names.hpp"

namespace wbi {

enum class EventSeverity : std::uint8_t {
  debug,    // for whoever digs
  info,     // a state change that is part of normal operation (a start, a switch)
  warning,  // something went wrong and was handled (a watchdog trip, a fallback)
  error,    // something went wrong and was not handled (a process died)
  fatal,    // the run cannot go on
};

template <>
struct EnumNames<EventSeverity> {
  static constexpr std::array names{"DEBUG", "INFO", "WARNING", "ERROR", "FATAL"};
};

constexpr const char* to_string(EventSeverity severity) { return enum_name(severity); }

enum class EventKind : std::uint8_t {
  process_started,      // launcher: a process of the deploy file started
  process_exited,       // launcher: it ended (its exit code or signal in the text)
  process_respawned,    // launcher: it was started again
  process_hung,         // launcher: no heartbeat or loop iteration for hang_timeout
  lifecycle,            // a component changed lifecycle state
  loop_stall,           // a periodic loop (or the real-time clock) ran late
  watchdog_trip,        // the robot held or damped joints that got no command
  claim_changed,        // joints were claimed or released
  claim_forced,         // joints were taken from their owner with force
  commands_rejected,    // commands or parameters were refused (the first of a burst)
  producer_restarted,   // a consumer saw a new incarnation of its producer
  divergence,           // a simulation or an estimate left its valid range
  controller_switched,  // the controller host changed its active controller
  controller_fallback,  // the controller host fell back to hold
  parameter_changed,    // a live parameter took a new value
  reference_stale,      // a controller's reference input went stale
};

template <>
struct EnumNames<EventKind> {
  static constexpr std::array names{
      "PROCESS_STARTED",     "PROCESS_EXITED",      "PROCESS_RESPAWNED",  "PROCESS_HUNG",
      "LIFECYCLE",           "LOOP_STALL",          "WATCHDOG_TRIP",      "CLAIM_CHANGED",
      "CLAIM_FORCED",        "COMMANDS_REJECTED",   "PRODUCER_RESTARTED", "DIVERGENCE",
      "CONTROLLER_SWITCHED", "CONTROLLER_FALLBACK", "PARAMETER_CHANGED",  "REFERENCE_STALE"};
};

constexpr const char* to_string(EventKind kind) { return enum_name(kind); }

}  // namespace wbi
