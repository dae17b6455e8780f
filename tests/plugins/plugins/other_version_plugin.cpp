// A plugin built against another wbi version (its entry point written out).
#include <wbi/plugin.hpp>

namespace {
void register_nothing(wbi::Catalog& /*catalog*/) {}
}  // namespace

extern "C" __attribute__((visibility("default"))) const wbi::PluginEntry* wbi_plugin_entry() {
  static const wbi::PluginEntry entry{wbi::kPluginEntryVersion, "0.0.9", WBI_PLUGIN_ABI,
                                      &register_nothing};
  return &entry;
}
