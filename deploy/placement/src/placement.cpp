#include "wbi/deploy/placement.hpp"

#include <cstdlib>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <vector>

namespace wbi::deploy {

namespace {

const char* environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : nullptr;
}

[[noreturn]] void fail(const std::string& file, const YAML::Node& node, const std::string& field,
                       const std::string& what) {
  std::string where = file;
  if (node.IsDefined()) {
    where += ":" + std::to_string(node.Mark().line + 1);
  }
  throw std::runtime_error(where + ": " + field + ": " + what);
}

void only_keys(const std::string& file, const YAML::Node& map, const std::string& field,
               const std::set<std::string>& known) {
  if (!map.IsMap()) {
    fail(file, map, field, "expected a mapping");
  }
  for (const auto& entry : map) {
    if (known.count(entry.first.Scalar()) == 0) {
      std::string list;
      for (const auto& key : known) {
        list += (list.empty() ? "" : ", ") + key;
      }
      fail(file, entry.first, field + "." + entry.first.Scalar(),
           "unknown key (known: " + list + ")");
    }
  }
}

std::string text(const std::string& file, const YAML::Node& node, const std::string& field) {
  if (!node.IsScalar() || node.Scalar().empty()) {
    fail(file, node, field, "expected a non-empty string");
  }
  return node.Scalar();
}

std::vector<std::string> text_list(const std::string& file, const YAML::Node& node,
                                   const std::string& field) {
  if (!node.IsSequence()) {
    fail(file, node, field, "expected a list of addresses");
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    out.push_back(text(file, node[i], field + "[" + std::to_string(i) + "]"));
  }
  return out;
}

dds::Discovery discovery_named(const std::string& name, const std::string& where) {
  if (name == "localhost") return dds::Discovery::localhost;
  if (name == "multicast") return dds::Discovery::multicast;
  if (name == "peers") return dds::Discovery::peers;
  if (name == "server") return dds::Discovery::server;
  throw std::runtime_error(where + ": must be localhost, multicast, peers or server, got '" + name +
                           "'");
}

std::vector<std::string> comma_list(const std::string& value) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= value.size()) {
    const auto end = std::min(value.find(',', start), value.size());
    if (end > start) {
      out.push_back(value.substr(start, end - start));
    }
    start = end + 1;
  }
  return out;
}

void read_network(const std::string& file, const YAML::Node& network,
                  dds::ParticipantOptions& options) {
  only_keys(file, network, "network", {"discovery", "peers", "interfaces", "server"});
  if (network["discovery"]) {
    options.discovery = discovery_named(
        text(file, network["discovery"], "network.discovery"),
        file + ":" + std::to_string(network["discovery"].Mark().line + 1) + ": network.discovery");
  } else {
    options.discovery = dds::Discovery::multicast;  // a network block means other hosts
  }
  if (network["peers"]) {
    options.network.peers = text_list(file, network["peers"], "network.peers");
  }
  if (network["interfaces"]) {
    options.network.interfaces = text_list(file, network["interfaces"], "network.interfaces");
  }
  if (network["server"]) {
    options.network.discovery_server = text(file, network["server"], "network.server");
  }
}

// The security block; WBI_DDS_SECURITY_DIRECTORY replaces its directory (and
// turns security on for a file without the block).
void read_security(const std::string& file, const YAML::Node& root, const std::string& identity,
                   dds::ParticipantOptions& options) {
  const YAML::Node security = root[kSecurityKey];
  const char* directory_override = environment("WBI_DDS_SECURITY_DIRECTORY");
  if (!security && directory_override == nullptr) {
    return;
  }
  std::filesystem::path directory;
  std::string identity_name = identity;
  if (security) {
    only_keys(file, security, "security", {"directory", "identity"});
    if (!security["directory"] && directory_override == nullptr) {
      fail(file, security, "security.directory", "missing");
    }
    if (security["directory"]) {
      directory = text(file, security["directory"], "security.directory");
      if (directory.is_relative()) {
        directory = std::filesystem::path(file).parent_path() / directory;
      }
    }
    if (security["identity"]) {
      identity_name = text(file, security["identity"], "security.identity");
    }
  }
  const std::string where =
      directory_override != nullptr
          ? std::string("WBI_DDS_SECURITY_DIRECTORY")
          : file + ":" + std::to_string(security.Mark().line + 1) + ": security.directory";
  if (directory_override != nullptr) {
    directory = directory_override;
  }
  if (!std::filesystem::is_directory(directory)) {
    throw std::runtime_error(where + ": no such directory: " + directory.string() +
                             " (create it with scripts/wbi-security-setup DEPLOY " +
                             directory.string() + ")");
  }
  if (identity_name.empty()) {
    fail(file, security, "security.identity", "missing (no process name to default to)");
  }
  options.security.directory = directory.string();
  options.security.identity = identity_name;
}

}  // namespace

void read_placement(const YAML::Node& root, const std::string& file, const std::string& identity,
                    dds::ParticipantOptions& options) {
  if (const YAML::Node network = root[kNetworkKey]) {
    read_network(file, network, options);
  }
  read_security(file, root, identity, options);
  if (const char* value = environment("WBI_DDS_DISCOVERY")) {
    options.discovery = discovery_named(value, "WBI_DDS_DISCOVERY");
  }
  if (const char* value = environment("WBI_DDS_PEERS")) {
    options.network.peers = comma_list(value);
  }
  if (const char* value = environment("WBI_DDS_INTERFACES")) {
    options.network.interfaces = comma_list(value);
  }
  if (const char* value = environment("WBI_DDS_DISCOVERY_SERVER")) {
    options.network.discovery_server = value;
  }
}

}  // namespace wbi::deploy
