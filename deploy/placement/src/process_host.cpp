// One process of a deploy file as the runtime's host document: the deploy
// format is read here, not in the runtime (wbi/runtime/host.hpp).
#include "wbi/deploy/process_host.hpp"

#include <algorithm>
#include <stdexcept>

#include <wbi/vocabulary/joined_names.hpp>

namespace wbi::deploy {

namespace {

const ProcessSpec& find_process(const DeployFile& deploy, const std::string& name) {
  const auto found = std::find_if(deploy.processes.begin(), deploy.processes.end(),
                                  [&](const ProcessSpec& process) { return process.name == name; });
  if (found == deploy.processes.end()) {
    throw std::runtime_error(deploy.path.string() + ": no process named '" + name +
                             "' in the deploy file");
  }
  return *found;
}

}  // namespace

YAML::Node process_host_document(const DeployFile& deploy,
                                 const std::vector<std::string>& processes) {
  if (processes.empty()) {
    throw std::runtime_error(deploy.path.string() + ": no process named to host");
  }
  YAML::Node components(YAML::NodeType::Sequence);
  // Each process's plugins: the file's, then its own (the loader skips a repeat).
  YAML::Node plugins(YAML::NodeType::Sequence);
  for (const auto& name : processes) {
    const ProcessSpec& process = find_process(deploy, name);
    if (!process.hosts_components) {
      throw std::runtime_error(deploy.path.string() + ":" + std::to_string(process.line) +
                               ": process '" + name + "' has no 'components' to host");
    }
    for (const auto& component : process.component_nodes) {
      components.push_back(component);
    }
    for (const auto& plugin : process.plugins) {
      plugins.push_back(plugin);
    }
  }
  YAML::Node host;
  host["components"] = components;
  if (plugins.size() > 0) {
    host["plugins"] = plugins;
  }
  return host;
}

ProcessHost load_process_host(const std::string& deploy_file, const std::string& processes) {
  const DeployFile deploy = read_deploy_file(deploy_file);
  return {deploy.join, process_host_document(deploy, split_names(processes, ','))};
}

}  // namespace wbi::deploy
