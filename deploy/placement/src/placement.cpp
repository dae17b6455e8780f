#include "wbi/deploy/placement.hpp"

#include <cstdlib>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <vector>

#include <wbi/dds/join_options.hpp>

namespace wbi::deploy {

namespace {

[[noreturn]] void fail(const std::string& file, const YAML::Node& node, const std::string& field,
                       const std::string& what) {
  std::string where = file;
  if (node.IsDefined()) {
    where += ':';  // not ":" + to_string(...): GCC 12's -Wrestrict false positive at -O3
    where += std::to_string(node.Mark().line + 1);
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

void read_network(const std::string& file, const YAML::Node& network,
                  dds::ParticipantOptions& options) {
  only_keys(file, network, "network", {"discovery", "peers", "interfaces", "server"});
  if (network["discovery"]) {
    try {
      options.discovery =
          dds::discovery_named(text(file, network["discovery"], "network.discovery"),
                               file + ":" + std::to_string(network["discovery"].Mark().line + 1) +
                                   ": network.discovery");
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error(error.what());
    }
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

// The security block. Without one, the identity is still recorded, so that a
// security directory given later (environment, flags) turns security on as it.
void read_security(const std::string& file, const YAML::Node& root, const std::string& identity,
                   dds::ParticipantOptions& options) {
  if (options.security.identity.empty()) {
    options.security.identity = identity;
  }
  const YAML::Node security = root[kSecurityKey];
  if (!security) {
    return;
  }
  only_keys(file, security, "security", {"directory", "identity"});
  if (!security["directory"]) {
    fail(file, security, "security.directory", "missing");
  }
  std::filesystem::path directory = text(file, security["directory"], "security.directory");
  if (directory.is_relative()) {
    directory = std::filesystem::path(file).parent_path() / directory;
  }
  // Not checked here: the environment or a flag may replace it (a deploy file
  // shipped without its keys); the participant names a missing file.
  if (security["identity"]) {
    options.security.identity = text(file, security["identity"], "security.identity");
  } else if (!identity.empty()) {
    options.security.identity = identity;
  }
  if (options.security.identity.empty()) {
    fail(file, security, "security.identity", "missing (no process name to default to)");
  }
  options.security.directory = directory.string();
}

}  // namespace

void read_placement(const YAML::Node& root, const std::string& file, const std::string& identity,
                    dds::ParticipantOptions& options) {
  if (const YAML::Node network = root[kNetworkKey]) {
    read_network(file, network, options);
  }
  read_security(file, root, identity, options);
}

YAML::Node load_deploy_file(const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(file + ": cannot read the deploy file");
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(file + ":" + std::to_string(error.mark.line + 1) + ": " + error.msg);
  }
  if (!root.IsMap()) {
    throw std::runtime_error(file + ": a deploy file is a map");
  }
  return root;
}

void read_join_options(const std::string& file, const std::string& identity,
                       dds::ParticipantOptions& options) {
  const YAML::Node root = load_deploy_file(file);
  if (const YAML::Node domain = root["domain_id"]) {
    try {
      options.domain_id =
          dds::domain_id_named(domain.IsScalar() ? domain.Scalar() : "",
                               file + ":" + std::to_string(domain.Mark().line + 1) + ": domain_id");
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error(error.what());
    }
  }
  if (const YAML::Node qos_file = root["qos_file"]) {
    std::filesystem::path path = text(file, qos_file, "qos_file");
    if (path.is_relative()) {
      path = std::filesystem::path(file).parent_path() / path;
    }
    if (!std::filesystem::exists(path)) {
      fail(file, qos_file, "qos_file", "no such file: " + path.string());
    }
    options.qos_file = path.string();
  }
  read_placement(root, file, identity, options);
}

}  // namespace wbi::deploy
