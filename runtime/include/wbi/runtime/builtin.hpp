// Component types that come with the runtime.
//   idle   does nothing in its cycle: its status shows the loop timing a host
//          achieves at a given rate (a smoke test for a deploy).
#pragma once

#include "wbi/runtime/registry.hpp"

namespace wbi::runtime {

void register_builtin_components(Registry& registry);

}  // namespace wbi::runtime
