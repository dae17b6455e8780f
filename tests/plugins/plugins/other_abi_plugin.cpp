// A plugin built with other compiler settings (here: another Eigen alignment).
#include <wbi/plugin.hpp>

namespace {
void register_nothing(wbi::Catalog& /*catalog*/) {}
}  // namespace

extern "C" __attribute__((visibility("default"))) const wbi::PluginEntry* wbi_plugin_entry() {
  static const wbi::PluginEntry entry{wbi::kPluginEntryVersion, WBI_VERSION_STRING,
                                      WBI_PLUGIN_STDLIB ", eigen-align 64", &register_nothing};
  return &entry;
}
