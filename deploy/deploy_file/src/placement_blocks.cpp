#include "wbi/deploy/placement_blocks.hpp"

#include <filesystem>
#include <stdexcept>

#include <wbi/dds/join_options.hpp>

#include "yaml_fields.hpp"

namespace wbi::deploy {

namespace {

void read_network(const detail::YamlFields& in, const YAML::Node& network, Placement& placement) {
  in.only_keys(network, "network", {"discovery", "peers", "interfaces", "server"});
  placement.discovery = dds::Discovery::multicast;  // a network block means other hosts
  if (const YAML::Node mode = network["discovery"]) {
    try {
      placement.discovery = dds::discovery_named(in.non_empty_text(mode, "network.discovery"),
                                                 in.where(mode) + ": network.discovery");
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error(error.what());
    }
  }
  if (network["peers"]) {
    placement.peers =
        in.non_empty_text_list(network["peers"], "network.peers", "a list of addresses");
  }
  if (network["interfaces"]) {
    placement.interfaces =
        in.non_empty_text_list(network["interfaces"], "network.interfaces", "a list of addresses");
  }
  if (network["server"]) {
    placement.discovery_server = in.non_empty_text(network["server"], "network.server");
  }
}

void read_security(const detail::YamlFields& in, const YAML::Node& security, Placement& placement) {
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
  placement.security_directory = directory.string();
  if (security["identity"]) {
    placement.security_identity = in.non_empty_text(security["identity"], "security.identity");
  }
  placement.security_where = in.where(security);
}

}  // namespace

Placement read_placement_blocks(const YAML::Node& root, const std::string& file) {
  const detail::YamlFields in(file);
  Placement placement;
  if (const YAML::Node network = root[kNetworkKey]) {
    read_network(in, network, placement);
  }
  if (const YAML::Node security = root[kSecurityKey]) {
    read_security(in, security, placement);
  }
  return placement;
}

void apply_placement(const Placement& placement, const std::string& identity,
                     dds::ParticipantOptions& options) {
  if (placement.discovery) {
    options.discovery = *placement.discovery;
  }
  if (placement.peers) {
    options.network.peers = *placement.peers;
  }
  if (placement.interfaces) {
    options.network.interfaces = *placement.interfaces;
  }
  if (placement.discovery_server) {
    options.network.discovery_server = *placement.discovery_server;
  }
  // Without a security block the identity is still recorded, so that a
  // security directory given later (environment, flags) turns security on as it.
  if (options.security.identity.empty()) {
    options.security.identity = identity;
  }
  if (placement.security_directory.empty()) {
    return;
  }
  if (!placement.security_identity.empty()) {
    options.security.identity = placement.security_identity;
  } else if (!identity.empty()) {
    options.security.identity = identity;
  }
  if (options.security.identity.empty()) {
    throw std::runtime_error(placement.security_where +
                             ": security.identity: missing (no process name to default to)");
  }
  options.security.directory = placement.security_directory;
}

void read_placement(const YAML::Node& root, const std::string& file, const std::string& identity,
                    dds::ParticipantOptions& options) {
  apply_placement(read_placement_blocks(root, file), identity, options);
}

}  // namespace wbi::deploy
