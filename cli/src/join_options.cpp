#include "join_options.hpp"

#include <stdexcept>

#include <wbi/deploy/placement.hpp>

namespace wbi::cli {

void add_join_options(Options& options, bool with_deploy, const std::string& identity) {
  if (with_deploy) {
    options.option("deploy", "FILE",
                   "join the deployment FILE describes: its domain_id, qos_file, network and "
                   "security blocks");
  }
  options.option("domain", "ID", "DDS domain id [0, 231] (else WBI_DOMAIN_ID, else 0)");
  options.option("discovery", "MODE", "localhost | multicast | peers | server (WBI_DDS_DISCOVERY)");
  options.option("peers", "A,B", "initial peers, address[:port] (WBI_DDS_PEERS; implies peers)");
  options.option("interfaces", "A,B",
                 "addresses of the interfaces DDS may use (WBI_DDS_INTERFACES; implies multicast)");
  options.option("discovery-server", "ADDR:PORT",
                 "a Fast DDS discovery server (WBI_DDS_DISCOVERY_SERVER; implies server)");
  options.option("qos-file", "FILE", "QoS profiles XML (WBI_QOS_FILE)");
  options.option("security", "DIR",
                 "DDS Security files from scripts/wbi-security-setup (WBI_DDS_SECURITY_DIRECTORY)");
  options.option("identity", "NAME",
                 "the identity in DIR to join as (WBI_DDS_SECURITY_IDENTITY" +
                     (identity.empty() ? std::string(")") : "; default: " + identity + ")"));
}

dds::ParticipantOptions join_options(const Options& options, const std::string& name,
                                     const std::string& default_identity) {
  dds::ParticipantOptions join;
  join.name = name;
  if (const auto file = options.get_optional("deploy")) {
    try {
      deploy::read_join_options(*file, default_identity, join);
    } catch (const std::runtime_error& error) {
      throw UsageError(std::string("--deploy ") + error.what());
    }
  }
  // The file's security.identity is its processes'; a tool joins as its own.
  join.security.identity = default_identity;
  dds::apply_environment(join);
  dds::apply(join_flags(options), join);
  if (join.security.enabled() && join.security.identity.empty()) {
    throw UsageError("the deployment is secured (" + join.security.directory +
                     "): give --identity NAME, an identity of that directory allowed to publish");
  }
  return join;
}

dds::JoinOverrides join_flags(const Options& options) {
  dds::JoinOverrides flags;
  try {
    if (const auto value = options.get_optional("domain")) {
      flags.domain_id = dds::domain_id_named(*value, "--domain");
    }
    if (const auto value = options.get_optional("discovery")) {
      flags.discovery = dds::discovery_named(*value, "--discovery");
    }
  } catch (const std::invalid_argument& error) {
    throw UsageError(error.what());
  }
  if (const auto value = options.get_optional("peers")) {
    flags.peers = dds::comma_list(*value);
  }
  if (const auto value = options.get_optional("interfaces")) {
    flags.interfaces = dds::comma_list(*value);
  }
  flags.discovery_server = options.get_optional("discovery-server");
  flags.qos_file = options.get_optional("qos-file");
  flags.security_directory = options.get_optional("security");
  flags.identity = options.get_optional("identity");
  return flags;
}

}  // namespace wbi::cli
