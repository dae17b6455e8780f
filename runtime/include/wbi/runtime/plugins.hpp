// Loading plugins (wbi/plugin.hpp) into a process's catalog.
//
// A plugin is named by path (it has a '/' or ends in ".so"; a relative path is
// taken from `near`, the folder of the file that names it) or by name: `NAME`
// is looked for as libNAME.so, then NAME.so, in the folders of
// plugin_search_path(). Each file is opened once (RTLD_NOW | RTLD_LOCAL: a
// missing symbol is an error at load, not in the middle of a run), checked
// (its entry point, the wbi version and ABI it was built for) and asked to
// register its types, which are then attributed to it. Plugins are never
// unloaded: the objects made from them live as long as the process.
//
// Every refusal is a PluginError of one line that names the file and says
// what to do: not found (with the folders searched), cannot be opened (the
// loader's reason), no entry point, another wbi version or ABI (both named), a
// type registered twice (both providers named), a registration that threw.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <wbi/catalog.hpp>

namespace YAML {
class Node;
}

namespace wbi::runtime {

class PluginError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The plugin with the project's own types (components, controllers, engines):
// every program that makes types by name loads it first.
inline constexpr const char* kBuiltinPlugin = "wbi_builtin";
// Folders searched before the default ones, ':'-separated.
inline constexpr const char* kPluginPathVariable = "WBI_PLUGIN_PATH";

// In order: the folders of WBI_PLUGIN_PATH, `near` (when not empty), and the
// running program's own plugin folder, <its folder>/../lib/wbi/plugins (the
// install's <prefix>/lib/wbi/plugins, or the build tree's lib/wbi/plugins).
std::vector<std::filesystem::path> plugin_search_path(const std::filesystem::path& near = {});

// The file `spec` names (see above). Throws PluginError.
std::filesystem::path find_plugin(const std::string& spec, const std::filesystem::path& near = {});

// The `plugins:` list of a host document (or a deploy file's process): names or
// paths, in load order. Throws ParameterError naming the file and line.
std::vector<std::string> plugins_of(const YAML::Node& document, const std::string& file);

class PluginLoader {
 public:
  explicit PluginLoader(Catalog& catalog) : catalog_(catalog) {}

  // Loads the plugin `spec` names; a file already loaded is skipped. Throws PluginError.
  void load(const std::string& spec, const std::filesystem::path& near = {});
  // The catalog's steps that wait for every plugin (Catalog::finish_loading).
  // Throws PluginError naming the provider of the step that threw.
  void finish();

  const std::vector<std::filesystem::path>& loaded() const { return loaded_; }

 private:
  Catalog& catalog_;
  std::vector<std::filesystem::path> loaded_;
};

// Loads the built-in plugin, then `specs`, then finishes: what a program does
// before it makes the types a deploy or host file names. Returns the files
// loaded, in order.
std::vector<std::filesystem::path> load_plugins(Catalog& catalog,
                                                const std::vector<std::string>& specs,
                                                const std::filesystem::path& near = {});

// A plugin's short name: its file name without "lib" and ".so".
std::string plugin_name(const std::filesystem::path& file);

// What a catalog holds, for `wbi_host --help` and `wbi plugins`: each kind,
// then one line per type: its name, the plugin it comes from, its description.
std::string describe_catalog(const Catalog& catalog);

}  // namespace wbi::runtime
