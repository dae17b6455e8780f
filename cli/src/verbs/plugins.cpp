// `wbi plugins [PLUGIN...] [--deploy FILE]`: the types a process can make by
// name (components, controllers, engines), each with the plugin it comes
// from: the built-in plugin's, the named plugins', and those of a deploy
// file's `plugins:` (every process's). Loads them as wbi_host does, so a
// plugin it refuses is refused the same way (one line, exit 1).
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <wbi/catalog.hpp>
#include <wbi/launch/deploy_file.hpp>
#include <wbi/runtime/plugins.hpp>

#include "../options.hpp"
#include "verbs.hpp"

namespace wbi::cli {

int run_plugins(Args args) {
  Options opts("wbi plugins [PLUGIN...] [--deploy FILE]",
               "List the component types, controller types and engines a process can make, "
               "with the plugin each comes from: the built-in plugin, the PLUGINs (names "
               "searched in $WBI_PLUGIN_PATH then wbi's plugin folder, or paths), and the "
               "plugins a deploy file names.");
  opts.option("deploy", "FILE", "also load the plugins this deploy file names");
  opts.rest("PLUGIN", "a plugin's name or path");
  opts.example("wbi plugins", "what the built-in plugin brings");
  opts.example("wbi plugins --deploy deploy/demo.yaml",
               "with the plugins a deploy file names (deploy/demo.yaml: none more)");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  std::vector<std::string> specs = opts.rest_values();
  std::filesystem::path near;
  if (const auto deploy_path = opts.get_optional("deploy")) {
    const launch::DeployFile deploy = wbi::deploy::read_deploy_file(*deploy_path);
    near = deploy.path.parent_path();
    for (const auto& process : deploy.processes) {
      specs.insert(specs.end(), process.plugins.begin(), process.plugins.end());
    }
  }
  Catalog catalog;
  const auto loaded = runtime::load_plugins(catalog, specs, near);
  std::cout << "plugins:\n";
  for (const auto& file : loaded) {
    std::cout << "  " << runtime::plugin_name(file) << "  " << file.string() << "\n";
  }
  std::cout << "\n"
            << runtime::describe_catalog(catalog)
            << "(and `hold`, every controller host's own fallback)\n";
  return kExitOk;
}

}  // namespace wbi::cli
