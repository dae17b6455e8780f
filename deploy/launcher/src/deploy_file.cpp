#include "wbi/launch/deploy_file.hpp"

#include <set>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include <wbi/catalog.hpp>
#include <wbi/deploy/placement.hpp>
#include <wbi/runtime/plugins.hpp>

namespace wbi::launch {

namespace {

// Errors name the file, the line of the offending node and the field path.
class Reader {
 public:
  explicit Reader(std::filesystem::path path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& field,
                         const std::string& what) const {
    std::string message = path_.string();
    if (node.IsDefined()) {
      message += ':';
      message += std::to_string(node.Mark().line + 1);
    }
    message += ": ";
    message += field;
    message += ": ";
    message += what;
    throw std::runtime_error(message);
  }

  void only_keys(const YAML::Node& map, const std::string& field,
                 const std::set<std::string>& allowed) const {
    if (!map.IsMap()) {
      fail(map, field, "expected a mapping");
    }
    for (const auto& entry : map) {
      const auto key = entry.first.as<std::string>();
      if (allowed.count(key) == 0) {
        std::string known;
        for (const auto& k : allowed) {
          known += (known.empty() ? "" : ", ") + k;
        }
        fail(entry.first, field.empty() ? key : field + "." + key,
             "unknown key (known: " + known + ")");
      }
    }
  }

  template <class T>
  T scalar(const YAML::Node& node, const std::string& field, const char* expected) const {
    if (!node.IsScalar()) {
      fail(node, field, std::string("expected ") + expected);
    }
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      fail(node, field, std::string("expected ") + expected + ", got '" + node.Scalar() + "'");
    }
  }

  std::map<std::string, std::string> string_map(const YAML::Node& node,
                                                const std::string& field) const {
    if (!node.IsMap()) {
      fail(node, field, "expected a mapping of names to values");
    }
    std::map<std::string, std::string> out;
    for (const auto& entry : node) {
      const auto key = entry.first.as<std::string>();
      out[key] = scalar<std::string>(entry.second, field + "." + key, "a value");
    }
    return out;
  }

  std::vector<std::string> string_list(const YAML::Node& node, const std::string& field) const {
    if (!node.IsSequence()) {
      fail(node, field, "expected a list");
    }
    std::vector<std::string> out;
    for (std::size_t i = 0; i < node.size(); ++i) {
      out.push_back(
          scalar<std::string>(node[i], field + "[" + std::to_string(i) + "]", "a string"));
    }
    return out;
  }

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

RespawnPolicy read_respawn(const Reader& in, const YAML::Node& node, const std::string& field) {
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

ProcessSpec read_process(const Reader& in, const YAML::Node& node, const std::string& field,
                         const std::vector<std::string>& plugins) {
  in.only_keys(node, field,
               {"name", "command", "components", "environment", "required", "respawn", "wait_for",
                "shutdown_on_exit", "hang_timeout", "host", "plugins"});
  ProcessSpec process;
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
  if (has_command) {
    process.command = in.string_list(node["command"], field + ".command");
    if (process.command.empty()) {
      in.fail(node["command"], field + ".command", "is empty");
    }
  } else {
    if (!node["components"].IsSequence() || node["components"].size() == 0) {
      in.fail(node["components"], field + ".components", "expected a non-empty list of components");
    }
    process.hosts_components = true;
    // host: a wbi_host of your own (its main with more component types registered).
    const std::string host =
        node["host"] ? in.scalar<std::string>(node["host"], field + ".host", "a program")
                     : "wbi_host";
    if (host.empty()) {
      in.fail(node["host"], field + ".host", "is empty");
    }
    process.command = {host, in.path().string(), "--process", process.name};
    for (const auto& component : node["components"]) {
      if (component.IsMap() && component["name"] && component["name"].IsScalar()) {
        process.components.push_back(component["name"].as<std::string>());
      }  // else wbi_host names the mistake
    }
  }
  if (node["plugins"]) {
    if (!has_components) {
      in.fail(node["plugins"], field + ".plugins",
              "needs 'components' (plugins bring the types of components and controllers)");
    }
    process.plugins = plugins;
    for (auto& plugin : in.string_list(node["plugins"], field + ".plugins")) {
      process.plugins.push_back(std::move(plugin));
    }
  } else if (has_components) {
    process.plugins = plugins;
  }
  if (node["host"] && !has_components) {
    in.fail(node["host"], field + ".host", "needs 'components' (it is the program that runs them)");
  }
  if (node["hang_timeout"]) {
    if (!has_components) {
      in.fail(node["hang_timeout"], field + ".hang_timeout",
              "needs 'components' (the heartbeats watched are its components' status)");
    }
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
  if (const auto wait = node["wait_for"]) {
    in.only_keys(wait, field + ".wait_for", {"topics", "timeout"});
    if (wait["topics"]) {
      process.wait_for_topics = in.string_list(wait["topics"], field + ".wait_for.topics");
    }
    if (wait["timeout"]) {
      process.wait_timeout_s =
          in.scalar<double>(wait["timeout"], field + ".wait_for.timeout", "a number of seconds");
      if (process.wait_timeout_s <= 0) {
        in.fail(wait["timeout"], field + ".wait_for.timeout", "must be > 0");
      }
    }
  }
  return process;
}

}  // namespace

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

DeployFile load_deploy_file(const std::filesystem::path& path) {
  Reader in(path);
  YAML::Node root;
  try {
    root = YAML::LoadFile(path.string());
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(path.string() + ": cannot open the deploy file");
  } catch (const YAML::ParserException& e) {
    throw std::runtime_error(path.string() + ":" + std::to_string(e.mark.line + 1) +
                             ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) {
    throw std::runtime_error(path.string() +
                             ": a deploy file is a mapping with a 'processes' list");
  }
  in.only_keys(root, "",
               {"domain_id", "qos_file", "environment", "summary", "processes", "plugins",
                wbi::deploy::kNetworkKey, wbi::deploy::kSecurityKey});
  DeployFile deploy;
  deploy.path = path;
  if (root["domain_id"]) {
    const int id = in.scalar<int>(root["domain_id"], "domain_id", "an integer");
    if (id < 0 || id > 232) {
      in.fail(root["domain_id"], "domain_id", "must be in [0, 232]");
    }
    deploy.domain_id = id;
  }
  if (root["qos_file"]) {
    deploy.qos_file =
        path.parent_path() / in.scalar<std::string>(root["qos_file"], "qos_file", "a path");
    if (!std::filesystem::exists(deploy.qos_file)) {
      in.fail(root["qos_file"], "qos_file", "no such file: " + deploy.qos_file.string());
    }
  }
  if (root["environment"]) {
    deploy.environment = in.string_map(root["environment"], "environment");
  }
  const auto processes = root["processes"];
  if (!processes || !processes.IsSequence() || processes.size() == 0) {
    in.fail(processes ? processes : root, "processes", "expected a non-empty list of processes");
  }
  const std::vector<std::string> plugins =
      root["plugins"] ? in.string_list(root["plugins"], "plugins") : std::vector<std::string>{};
  std::set<std::string> names;
  for (std::size_t i = 0; i < processes.size(); ++i) {
    const std::string field = "processes[" + std::to_string(i) + "]";
    auto process = read_process(in, processes[i], field, plugins);
    if (!names.insert(process.name).second) {
      in.fail(processes[i]["name"], field + ".name", "'" + process.name + "' is used twice");
    }
    deploy.processes.push_back(std::move(process));
  }
  if (const auto summary = root["summary"]) {
    const bool list = summary.IsSequence();
    if (list && summary.size() == 0) {
      in.fail(summary, "summary", "expected {process, match} or a non-empty list of them");
    }
    for (std::size_t i = 0; i < (list ? summary.size() : 1); ++i) {
      const auto entry = list ? summary[i] : summary;
      const std::string field = list ? "summary[" + std::to_string(i) + "]" : "summary";
      in.only_keys(entry, field, {"process", "match"});
      SummarySpec spec;
      spec.process = in.scalar<std::string>(entry["process"], field + ".process", "a process name");
      spec.match = in.scalar<std::string>(entry["match"], field + ".match", "a text to find");
      if (names.count(spec.process) == 0) {
        in.fail(entry["process"], field + ".process", "no process named '" + spec.process + "'");
      }
      deploy.summaries.push_back(spec);
    }
  }
  dds::ParticipantOptions placement;
  wbi::deploy::read_placement(root, path.string(), "launcher", placement);
  deploy.discovery = placement.discovery;
  deploy.network = placement.network;
  deploy.security = placement.security;
  return deploy;
}

}  // namespace wbi::launch
