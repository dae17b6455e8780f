// A launch refuses a bad plugin before it starts anything.
#include <stdexcept>

#include <wbi/catalog.hpp>
#include <wbi/runtime/plugins.hpp>

#include "wbi/launch/deploy_file.hpp"

namespace wbi::launch {

void check_plugins(const DeployFile& deploy) {
  for (const ProcessSpec& process : deploy.processes) {
    if (!process.hosts_components) {
      continue;
    }
    Catalog catalog;
    try {
      runtime::load_plugins(catalog, process.plugins, deploy.path.parent_path());
    } catch (const std::exception& e) {
      throw std::runtime_error(deploy.path.string() + ": process '" + process.name +
                               "': " + e.what());
    }
  }
}

}  // namespace wbi::launch
