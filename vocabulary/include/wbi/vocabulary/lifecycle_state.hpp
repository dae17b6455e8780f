// Where a component or a robot backend is in its life: the one lifecycle-state
// enum of every layer (the component runtime, robot backends) and the wire's
// (idl/status.idl, LifecycleState), which follows it value for value. The
// states and transitions are ROS 2's managed-node ones (components/README.md).
#pragma once

#include <cstdint>

#include "wbi/vocabulary/enum_names.hpp"

namespace wbi {

enum class LifecycleState : std::uint8_t {
  unconfigured,  // created, no communication, no hardware open
  inactive,      // configured: reads allowed, no commands
  active,        // running: commands accepted
  finalized,     // shut down
};

template <>
struct EnumNames<LifecycleState> {
  static constexpr std::array names{"UNCONFIGURED", "INACTIVE", "ACTIVE", "FINALIZED"};
};

constexpr const char* to_string(LifecycleState state) { return enum_name(state); }

}  // namespace wbi
