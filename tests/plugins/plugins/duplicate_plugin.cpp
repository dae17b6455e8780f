// A plugin that registers a type name the built-in plugin has.
#include <wbi/plugin.hpp>
#include <wbi/runtime/registry.hpp>

#include "quiet_component.hpp"

namespace {}  // namespace

WBI_PLUGIN(catalog) {
  catalog.registry<wbi::runtime::Registry>().add<wbi::test::QuietComponent>("estimator",
                                                                            "not the estimator");
}
