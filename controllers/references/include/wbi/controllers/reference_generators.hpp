// Components that publish controllers' references (controllers/README.md,
// "References"): com_sinusoid, the balancing experiments' CoM reference.
#pragma once

#include "wbi/runtime/registry.hpp"

namespace wbi::controllers {

void register_reference_generators(runtime::Registry& registry);

}  // namespace wbi::controllers
