// A plugin: a shared library, built in a lab's own project against the
// installed wbi (find_package(wbi), wbi_add_plugin), that adds types to a
// process's catalog (wbi/catalog.hpp): controllers, components (planners,
// reference generators, estimators, a robot's driver), simulation engines.
// A deploy file names the plugins a process loads (`plugins:`); the loader
// (wbi/runtime/plugins.hpp) opens each, checks that it was built against this
// wbi version and ABI, and calls its registration once:
//
//   #include <wbi/controllers/controller.hpp>
//   #include <wbi/plugin.hpp>
//
//   WBI_PLUGIN(catalog) {
//     catalog.registry<wbi::controllers::ControllerRegistry>().add<MyPd>(
//         "my_pd", "PD about a posture the lab likes");
//   }
//
// The project's own types come the same way, from the plugin `wbi_builtin`.
// A registration may throw: the loader then refuses the plugin, naming it.
#pragma once

#include <Eigen/Core>  // the ABI below depends on Eigen's alignment

#include "wbi/catalog.hpp"
#include "wbi/version.hpp"

#define WBI_PLUGIN_STRINGIFY_(x) #x
#define WBI_PLUGIN_STRINGIFY(x) WBI_PLUGIN_STRINGIFY_(x)

#if defined(_LIBCPP_VERSION)
#define WBI_PLUGIN_STDLIB "libc++ " WBI_PLUGIN_STRINGIFY(_LIBCPP_VERSION)
#elif defined(_GLIBCXX_USE_CXX11_ABI)
#define WBI_PLUGIN_STDLIB "libstdc++ cxx11-abi " WBI_PLUGIN_STRINGIFY(_GLIBCXX_USE_CXX11_ABI)
#else
#define WBI_PLUGIN_STDLIB "unknown standard library"
#endif

// What must match between a program and its plugins besides the version:
// the standard library's ABI (std::string, std::function cross the boundary)
// and Eigen's static alignment (fixed-size members of the interface's structs
// move with -march; a mismatch corrupts them silently).
#define WBI_PLUGIN_ABI \
  WBI_PLUGIN_STDLIB ", eigen-align " WBI_PLUGIN_STRINGIFY(EIGEN_MAX_STATIC_ALIGN_BYTES)

namespace wbi {

// What a plugin's entry point returns (its layout is part of the contract:
// only ever extended at the end, with kPluginEntryVersion raised).
struct PluginEntry {
  int entry_version;    // kPluginEntryVersion of the plugin's build
  const char* version;  // WBI_VERSION_STRING of the plugin's build
  const char* abi;      // WBI_PLUGIN_ABI of the plugin's build
  void (*register_types)(Catalog& catalog);
};

inline constexpr int kPluginEntryVersion = 1;
// The entry point's symbol, extern "C".
inline constexpr const char* kPluginEntrySymbol = "wbi_plugin_entry";

}  // namespace wbi

// Defines the plugin's entry point; the block that follows is its
// registration, with `catalog_name` the process's catalog.
#define WBI_PLUGIN(catalog_name)                                                                   \
  static void wbi_plugin_register_types(::wbi::Catalog& catalog_name);                             \
  extern "C" __attribute__((visibility("default"))) const ::wbi::PluginEntry* wbi_plugin_entry() { \
    static const ::wbi::PluginEntry entry{::wbi::kPluginEntryVersion, WBI_VERSION_STRING,          \
                                          WBI_PLUGIN_ABI, &wbi_plugin_register_types};             \
    return &entry;                                                                                 \
  }                                                                                                \
  static void wbi_plugin_register_types(::wbi::Catalog& catalog_name)
