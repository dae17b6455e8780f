#include "wbi/runtime/plugins.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <system_error>

#include <yaml-cpp/yaml.h>

#include <wbi/plugin.hpp>

#include "wbi/runtime/parameters.hpp"

namespace wbi::runtime {

namespace fs = std::filesystem;

namespace {

bool names_a_path(const std::string& spec) {
  return spec.find('/') != std::string::npos ||
         (spec.size() > 3 && spec.compare(spec.size() - 3, 3, ".so") == 0);
}

// The running program's own plugin folder: <its folder>/../lib/wbi/plugins.
fs::path own_plugin_folder() {
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (error) {
    return {};
  }
  return (program.parent_path().parent_path() / WBI_INSTALL_LIBDIR / "wbi" / "plugins")
      .lexically_normal();
}

std::string folders_text(const std::vector<fs::path>& folders) {
  std::string text;
  for (const auto& folder : folders) {
    text += (text.empty() ? "" : ", ") + folder.string();
  }
  return text.empty() ? "no folder" : text;
}

}  // namespace

std::vector<fs::path> plugin_search_path(const fs::path& near) {
  std::vector<fs::path> folders;
  if (const char* variable = std::getenv(kPluginPathVariable)) {
    const std::string list = variable;
    for (std::size_t start = 0; start <= list.size();) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      if (end > start) {
        folders.emplace_back(list.substr(start, end - start));
      }
      start = end + 1;
    }
  }
  if (!near.empty()) {
    folders.push_back(near);
  }
  if (fs::path own = own_plugin_folder(); !own.empty()) {
    folders.push_back(std::move(own));
  }
  return folders;
}

fs::path find_plugin(const std::string& spec, const fs::path& near) {
  if (spec.empty()) {
    throw PluginError("plugin '': an empty name");
  }
  if (names_a_path(spec)) {
    fs::path path = spec;
    if (path.is_relative() && !near.empty()) {
      path = near / path;
    }
    if (!fs::is_regular_file(path)) {
      throw PluginError("plugin " + path.string() + ": no such file");
    }
    return fs::absolute(path).lexically_normal();
  }
  const auto folders = plugin_search_path(near);
  for (const auto& folder : folders) {
    for (const std::string& file : {"lib" + spec + ".so", spec + ".so"}) {
      if (const fs::path path = folder / file; fs::is_regular_file(path)) {
        return fs::absolute(path).lexically_normal();
      }
    }
  }
  throw PluginError("plugin '" + spec + "': not found (looked for lib" + spec + ".so and " + spec +
                    ".so in " + folders_text(folders) + "; set " + kPluginPathVariable +
                    " or name its path)");
}

std::vector<std::string> plugins_of(const YAML::Node& document, const std::string& file) {
  const YAML::Node list = document["plugins"];
  if (!list) {
    return {};
  }
  const std::string where = file + ":" + std::to_string(list.Mark().line + 1);
  if (!list.IsSequence()) {
    throw ParameterError(where + ": 'plugins' must be a list of plugin names or paths");
  }
  std::vector<std::string> specs;
  for (const auto& item : list) {
    if (!item.IsScalar() || item.Scalar().empty()) {
      throw ParameterError(file + ":" + std::to_string(item.Mark().line + 1) +
                           ": 'plugins': each entry is a plugin's name or path");
    }
    specs.push_back(item.Scalar());
  }
  return specs;
}

void PluginLoader::load(const std::string& spec, const fs::path& near) {
  const fs::path path = find_plugin(spec, near);
  for (const auto& loaded : loaded_) {
    if (loaded == path) {
      return;
    }
  }
  const std::string name = "plugin " + path.string();
  void* library = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* why = ::dlerror();
    throw PluginError(name + ": cannot be opened: " + (why ? why : "unknown reason"));
  }
  // Never dlclose'd: what it made may outlive this call (see the header).
  using Entry = const PluginEntry* (*)();
  auto* entry_point = reinterpret_cast<Entry>(::dlsym(library, kPluginEntrySymbol));
  if (!entry_point) {
    throw PluginError(name + ": no entry point '" + kPluginEntrySymbol +
                      "' (a plugin declares it with WBI_PLUGIN, wbi/plugin.hpp)");
  }
  const PluginEntry* entry = entry_point();
  if (!entry || entry->entry_version != kPluginEntryVersion) {
    throw PluginError(name + ": its entry point is of another kind (version " +
                      std::to_string(entry ? entry->entry_version : 0) + ", this program reads " +
                      std::to_string(kPluginEntryVersion) + "): rebuild it against this wbi");
  }
  if (std::string(entry->version) != WBI_VERSION_STRING) {
    throw PluginError(name + ": built against wbi " + entry->version + ", this program is wbi " +
                      WBI_VERSION_STRING + ": rebuild it against this wbi");
  }
  if (std::string(entry->abi) != WBI_PLUGIN_ABI) {
    throw PluginError(name + ": built for the ABI '" + entry->abi + "', this program's is '" +
                      WBI_PLUGIN_ABI + "': rebuild it with the same compiler settings");
  }
  const std::string before = catalog_.provider();
  catalog_.set_provider(path.string());
  try {
    entry->register_types(catalog_);
  } catch (const std::exception& e) {
    catalog_.set_provider(before);
    throw PluginError(name + ": its registration failed: " + e.what());
  } catch (...) {
    catalog_.set_provider(before);
    throw PluginError(name +
                      ": its registration failed with an exception that is not std::exception");
  }
  catalog_.set_provider(before);
  loaded_.push_back(path);
}

void PluginLoader::finish() {
  try {
    catalog_.finish_loading();
  } catch (const std::exception& e) {
    throw PluginError("plugin " + catalog_.provider() +
                      ": a step after loading failed: " + e.what());
  }
}

std::vector<fs::path> load_plugins(Catalog& catalog, const std::vector<std::string>& specs,
                                   const fs::path& near) {
  PluginLoader loader(catalog);
  loader.load(kBuiltinPlugin);
  for (const auto& spec : specs) {
    loader.load(spec, near);
  }
  loader.finish();
  return loader.loaded();
}

std::string plugin_name(const fs::path& file) {
  std::string name = file.filename().string();
  if (name.rfind("lib", 0) == 0) {
    name.erase(0, 3);
  }
  if (name.size() > 3 && name.compare(name.size() - 3, 3, ".so") == 0) {
    name.erase(name.size() - 3);
  }
  return name;
}

std::string describe_catalog(const Catalog& catalog) {
  std::string text;
  for (const RegistryBase* registry : catalog.registries()) {
    const auto entries = registry->listing();
    std::size_t name_width = 0, provider_width = 0;
    for (const auto& entry : entries) {
      name_width = std::max(name_width, entry.name.size());
      provider_width = std::max(provider_width, plugin_name(entry.provider).size());
    }
    text += (text.empty() ? "" : "\n") + registry->what() + "s (name, plugin, what it is):\n";
    for (const auto& entry : entries) {
      const std::string provider = plugin_name(entry.provider);
      text += "  " + entry.name + std::string(name_width - entry.name.size() + 2, ' ') + provider +
              std::string(provider_width - provider.size() + 2, ' ') + entry.description + "\n";
    }
  }
  return text;
}

}  // namespace wbi::runtime
