// The wire's enums are the vocabulary's (vocabulary/), value for value: the
// .idl files list the same enumerators in the same order, spelt as the
// vocabulary's to_string spells them (tests/vocabulary checks the names).
// Going onto the wire is a cast; coming off it is a range check, since a
// sample may carry any 32-bit value.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include <wbi/msg/commands.h>
#include <wbi/msg/description.h>
#include <wbi/msg/events.h>
#include <wbi/msg/status.h>
#include <wbi/vocabulary/control_mode.hpp>
#include <wbi/vocabulary/event.hpp>
#include <wbi/vocabulary/lifecycle_state.hpp>
#include <wbi/vocabulary/sensor_kind.hpp>

namespace wbi::msg {

static_assert(PWM == static_cast<int>(wbi::ControlMode::pwm) &&
                  enum_count<wbi::ControlMode>() == PWM + 1,
              "idl/commands.idl's ControlMode must follow wbi::ControlMode");
static_assert(FINALIZED == static_cast<int>(wbi::LifecycleState::finalized) &&
                  enum_count<wbi::LifecycleState>() == FINALIZED + 1,
              "idl/status.idl's LifecycleState must follow wbi::LifecycleState");
static_assert(GYROSCOPE == static_cast<int>(wbi::SensorKind::gyroscope) &&
                  enum_count<wbi::SensorKind>() == GYROSCOPE + 1,
              "idl/description.idl's SensorKind must follow wbi::SensorKind");
static_assert(FATAL == static_cast<int>(wbi::EventSeverity::fatal) &&
                  enum_count<wbi::EventSeverity>() == FATAL + 1,
              "idl/events.idl's EventSeverity must follow wbi::EventSeverity");
static_assert(REFERENCE_STALE == static_cast<int>(wbi::EventKind::reference_stale) &&
                  enum_count<wbi::EventKind>() == REFERENCE_STALE + 1,
              "idl/events.idl's EventKind must follow wbi::EventKind");

// ActuatorCommand.tick of a command that answers no lockstep tick: one sent
// before the controller computed any reference from a sample (its start-up mode
// switch, say). The robot applies such a command as any other, but its
// lockstep pacer does not step on it.
inline constexpr std::uint64_t kNoTick = std::numeric_limits<std::uint64_t>::max();

constexpr ControlMode to_wire(wbi::ControlMode mode) { return static_cast<ControlMode>(mode); }
constexpr LifecycleState to_wire(wbi::LifecycleState state) {
  return static_cast<LifecycleState>(state);
}
constexpr SensorKind to_wire(wbi::SensorKind kind) { return static_cast<SensorKind>(kind); }
constexpr EventSeverity to_wire(wbi::EventSeverity severity) {
  return static_cast<EventSeverity>(severity);
}
constexpr EventKind to_wire(wbi::EventKind kind) { return static_cast<EventKind>(kind); }

constexpr std::optional<wbi::ControlMode> from_wire(ControlMode mode) {
  return enum_from_value<wbi::ControlMode>(mode);
}
constexpr std::optional<wbi::LifecycleState> from_wire(LifecycleState state) {
  return enum_from_value<wbi::LifecycleState>(state);
}
constexpr std::optional<wbi::SensorKind> from_wire(SensorKind kind) {
  return enum_from_value<wbi::SensorKind>(kind);
}
constexpr std::optional<wbi::EventSeverity> from_wire(EventSeverity severity) {
  return enum_from_value<wbi::EventSeverity>(severity);
}
constexpr std::optional<wbi::EventKind> from_wire(EventKind kind) {
  return enum_from_value<wbi::EventKind>(kind);
}

}  // namespace wbi::msg
