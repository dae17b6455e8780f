// One process of a deploy file as the runtime's host document: the deploy
// format is read here, not in the runtime (wbi/runtime/host.hpp).
#include "wbi/deploy/process_host.hpp"

#include <stdexcept>

#include "wbi/deploy/placement.hpp"

#include <wbi/vocabulary/joined_names.hpp>

namespace wbi::deploy {

namespace {

std::string line_of(const std::string& file, const YAML::Node& node) {
  return file + ":" + std::to_string(node.Mark().line + 1);
}

// The entry of `processes` named `name`; throws naming the file when there is none.
YAML::Node find_process(const YAML::Node& deploy, const std::string& file,
                        const std::string& name) {
  const YAML::Node processes = deploy["processes"];
  if (processes && processes.IsSequence()) {
    for (const auto& entry : processes) {
      if (entry.IsMap() && entry["name"] && entry["name"].IsScalar() &&
          entry["name"].Scalar() == name) {
        return entry;
      }
    }
  }
  throw std::runtime_error(file + ": no process named '" + name + "' in the deploy file");
}

}  // namespace

YAML::Node process_host_document(const YAML::Node& deploy, const std::string& file,
                                 const std::vector<std::string>& processes) {
  if (processes.empty()) {
    throw std::runtime_error(file + ": no process named to host");
  }
  YAML::Node components(YAML::NodeType::Sequence);
  // The deploy file's plugins, then each process's (the loader skips a repeat).
  YAML::Node plugins(YAML::NodeType::Sequence);
  const auto add_plugins = [&](const YAML::Node& list) {
    if (list && list.IsSequence()) {
      for (const auto& plugin : list) {
        plugins.push_back(plugin);
      }
    }
  };
  add_plugins(deploy["plugins"]);
  for (const auto& name : processes) {
    const YAML::Node entry = find_process(deploy, file, name);
    add_plugins(entry["plugins"]);
    if (!entry["components"]) {
      throw std::runtime_error(line_of(file, entry) + ": process '" + name +
                               "' has no 'components' to host");
    }
    for (const auto& component : entry["components"]) {
      components.push_back(component);
    }
  }
  YAML::Node host;
  host["components"] = components;
  if (plugins.size() > 0) {
    host["plugins"] = plugins;
  }
  for (const char* key : {"domain_id", "qos_file", kNetworkKey, kSecurityKey}) {
    if (deploy[key]) {
      host[key] = deploy[key];
    }
  }
  return host;
}

YAML::Node process_host_document(const YAML::Node& deploy, const std::string& file,
                                 const std::string& process) {
  return process_host_document(deploy, file, std::vector<std::string>{process});
}

YAML::Node load_process_host(const std::string& deploy_file, const std::string& processes) {
  const std::vector<std::string> names = split_names(processes, ',');
  return process_host_document(load_deploy_file(deploy_file), deploy_file, names);
}

}  // namespace wbi::deploy
