// What produces controllers' references (controllers/README.md, "References"):
// com_sinusoid, the balancing experiments' CoM reference, as a component that
// publishes it from its own process, and as a planner (a controller type)
// chained to the balancer in the balancer's own host.
#pragma once

#include "wbi/controllers/controller.hpp"
#include "wbi/runtime/registry.hpp"

namespace wbi::controllers {

void register_reference_generators(runtime::Registry& registry);
void register_reference_planners(ControllerRegistry& registry);

}  // namespace wbi::controllers
