#include "process_entry.hpp"

#include <utility>

namespace wbi::deploy::detail {

namespace {

RespawnPolicy read_respawn(const YamlFields& in, const YAML::Node& node, const std::string& field) {
  in.only_keys(node, field, {"enabled", "delay", "max_retries"});
  RespawnPolicy policy;
  if (node["enabled"]) {
    policy.enabled = in.scalar<bool>(node["enabled"], field + ".enabled", "true or false");
  }
  if (node["delay"]) {
    policy.delay_s = in.scalar<double>(node["delay"], field + ".delay", "a number of seconds");
    if (policy.delay_s < 0) {
      in.fail(node["delay"], field + ".delay", "must be >= 0");
    }
  }
  if (node["max_retries"]) {
    policy.max_retries = in.scalar<int>(node["max_retries"], field + ".max_retries", "an integer");
    if (policy.max_retries < 0) {
      in.fail(node["max_retries"], field + ".max_retries", "must be >= 0");
    }
  }
  return policy;
}

void read_wait_for(const YamlFields& in, const YAML::Node& wait, const std::string& field,
                   ProcessSpec& process) {
  in.only_keys(wait, field, {"topics", "timeout"});
  if (wait["topics"]) {
    process.wait_for_topics = in.string_list(wait["topics"], field + ".topics");
  }
  if (wait["timeout"]) {
    process.wait_timeout_s =
        in.scalar<double>(wait["timeout"], field + ".timeout", "a number of seconds");
    if (process.wait_timeout_s <= 0) {
      in.fail(wait["timeout"], field + ".timeout", "must be > 0");
    }
  }
}

// components: the program that runs them (wbi_host, or `host:`) is started
// on this deploy file with --process NAME.
void read_components(const YamlFields& in, const YAML::Node& node, const std::string& field,
                     ProcessSpec& process) {
  const YAML::Node components = node["components"];
  if (!components.IsSequence() || components.size() == 0) {
    in.fail(components, field + ".components", "expected a non-empty list of components");
  }
  process.hosts_components = true;
  process.component_nodes = components;
  // host: a wbi_host of your own (its main with more component types registered).
  const std::string host = node["host"]
                               ? in.scalar<std::string>(node["host"], field + ".host", "a program")
                               : "wbi_host";
  if (host.empty()) {
    in.fail(node["host"], field + ".host", "is empty");
  }
  process.command = {host, in.file(), "--process", process.name};
  for (const auto& component : components) {
    if (component.IsMap() && component["name"] && component["name"].IsScalar()) {
      process.components.push_back(component["name"].Scalar());
    }  // else wbi_host names the mistake
  }
}

// Keys that only a components: process may have, and why.
void only_with_components(const YamlFields& in, const YAML::Node& node, const std::string& field,
                          bool has_components) {
  if (has_components) {
    return;
  }
  const std::pair<const char*, const char*> needs[] = {
      {"plugins", "plugins bring the types of components and controllers"},
      {"host", "it is the program that runs them"},
      {"hang_timeout", "the heartbeats watched are its components' status"}};
  for (const auto& [key, why] : needs) {
    if (node[key]) {
      in.fail(node[key], field + "." + key, std::string("needs 'components' (") + why + ")");
    }
  }
}

}  // namespace

ProcessSpec read_process(const YamlFields& in, const YAML::Node& node, const std::string& field,
                         const std::vector<std::string>& plugins) {
  in.only_keys(node, field,
               {"name", "command", "components", "environment", "required", "respawn", "wait_for",
                "shutdown_on_exit", "hang_timeout", "host", "plugins"});
  ProcessSpec process;
  process.line = node.Mark().line + 1;
  if (!node["name"]) {
    in.fail(node, field + ".name", "missing");
  }
  process.name = in.scalar<std::string>(node["name"], field + ".name", "a name");
  if (process.name.empty() || process.name.find_first_of(" \t/") != std::string::npos) {
    in.fail(node["name"], field + ".name", "must be a non-empty word without spaces or '/'");
  }
  const bool has_command = static_cast<bool>(node["command"]);
  const bool has_components = static_cast<bool>(node["components"]);
  if (has_command == has_components) {
    in.fail(node, field, "needs exactly one of 'command' or 'components'");
  }
  only_with_components(in, node, field, has_components);
  if (has_command) {
    process.command = in.string_list(node["command"], field + ".command");
    if (process.command.empty()) {
      in.fail(node["command"], field + ".command", "is empty");
    }
  } else {
    read_components(in, node, field, process);
    process.plugins = plugins;
  }
  if (node["plugins"]) {
    for (auto& plugin : in.string_list(node["plugins"], field + ".plugins")) {
      process.plugins.push_back(std::move(plugin));
    }
  }
  if (node["hang_timeout"]) {
    process.hang_timeout_s =
        in.scalar<double>(node["hang_timeout"], field + ".hang_timeout", "a number of seconds");
    if (!(process.hang_timeout_s > 0)) {
      in.fail(node["hang_timeout"], field + ".hang_timeout", "must be > 0");
    }
  }
  if (node["environment"]) {
    process.environment = in.string_map(node["environment"], field + ".environment");
  }
  if (node["required"]) {
    process.required = in.scalar<bool>(node["required"], field + ".required", "true or false");
  }
  if (node["shutdown_on_exit"]) {
    process.shutdown_on_exit =
        in.scalar<bool>(node["shutdown_on_exit"], field + ".shutdown_on_exit", "true or false");
  }
  if (node["respawn"]) {
    process.respawn = read_respawn(in, node["respawn"], field + ".respawn");
  }
  if (node["wait_for"]) {
    read_wait_for(in, node["wait_for"], field + ".wait_for", process);
  }
  return process;
}

}  // namespace wbi::deploy::detail
