#include "wbi/deploy/placement_blocks.hpp"

#include <filesystem>
#include <stdexcept>

#include <wbi/dds/join_options.hpp>

#include "yaml_fields.hpp"

namespace wbi::deploy {

namespace {

void read_network(const detail::YamlFields& in, const YAML::Node& network, JoinKeys& keys) {
  in.only_keys(network, "network", {"discovery", "peers", "interfaces", "server"});
  keys.discovery = dds::Discovery::multicast;  // a network block means other hosts
  if (const YAML::Node mode = network["discovery"]) {
    try {
      keys.discovery = dds::discovery_named(in.non_empty_text(mode, "network.discovery"),
                                            in.where(mode) + ": network.discovery");
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error(error.what());
    }
  }
  if (network["peers"]) {
    keys.peers = in.non_empty_text_list(network["peers"], "network.peers", "a list of addresses");
  }
  if (network["interfaces"]) {
    keys.interfaces =
        in.non_empty_text_list(network["interfaces"], "network.interfaces", "a list of addresses");
  }
  if (network["server"]) {
    keys.discovery_server = in.non_empty_text(network["server"], "network.server");
  }
}

void read_security(const detail::YamlFields& in, const YAML::Node& security, JoinKeys& keys) {
  in.only_keys(security, "security", {"directory", "identity"});
  if (!security["directory"]) {
    in.fail(security, "security.directory", "missing");
  }
  std::filesystem::path directory = in.non_empty_text(security["directory"], "security.directory");
  if (directory.is_relative()) {
    directory = std::filesystem::path(in.file()).parent_path() / directory;
  }
  // Not checked here: the environment or a flag may replace it (a deploy file
  // shipped without its keys); the participant names a missing file.
  keys.security_directory = directory.string();
  if (security["identity"]) {
    keys.identity = in.non_empty_text(security["identity"], "security.identity");
  }
  keys.security_where = in.where(security);
}

}  // namespace

JoinKeys read_placement_blocks(const YAML::Node& root, const std::string& file) {
  const detail::YamlFields in(file);
  JoinKeys keys;
  if (const YAML::Node network = root[kNetworkKey]) {
    read_network(in, network, keys);
  }
  if (const YAML::Node security = root[kSecurityKey]) {
    read_security(in, security, keys);
  }
  return keys;
}

void apply_join_keys(const JoinKeys& keys, const std::string& identity,
                     dds::ParticipantOptions& options) {
  // Without a security block the identity is still recorded, so that a
  // security directory given later (environment, flags) turns security on as it.
  if (options.security.identity.empty()) {
    options.security.identity = identity;
  }
  dds::JoinOverrides join = keys;
  if (join.security_directory && !join.identity && !identity.empty()) {
    join.identity = identity;
  }
  dds::apply(join, options);
  if (join.security_directory && options.security.identity.empty()) {
    throw std::runtime_error(keys.security_where +
                             ": security.identity: missing (no process name to default to)");
  }
}

void read_placement(const YAML::Node& root, const std::string& file, const std::string& identity,
                    dds::ParticipantOptions& options) {
  apply_join_keys(read_placement_blocks(root, file), identity, options);
}

}  // namespace wbi::deploy
