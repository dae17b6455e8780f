// The component libraries linked into wbi_host register their types here.
#pragma once

#include <wbi/runtime/registry.hpp>

namespace wbi::host {

void register_components(wbi::runtime::Registry& registry);

}  // namespace wbi::host
