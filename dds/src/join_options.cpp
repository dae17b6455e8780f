#include "wbi/dds/join_options.hpp"

#include "wbi/dds/domain_id.hpp"

#include <cstdlib>
#include <stdexcept>

namespace wbi::dds {

namespace {

std::optional<std::string> variable(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') {
    return std::nullopt;
  }
  return std::string(value);
}

}  // namespace

Discovery discovery_named(const std::string& name, const std::string& where) {
  if (name == "localhost") return Discovery::localhost;
  if (name == "multicast") return Discovery::multicast;
  if (name == "peers") return Discovery::peers;
  if (name == "server") return Discovery::server;
  throw std::invalid_argument(where + ": must be localhost, multicast, peers or server, got '" +
                              name + "'");
}

const char* discovery_name(Discovery discovery) {
  switch (discovery) {
    case Discovery::localhost:
      return "localhost";
    case Discovery::multicast:
      return "multicast";
    case Discovery::peers:
      return "peers";
    case Discovery::server:
      return "server";
  }
  return "?";
}

std::vector<std::string> comma_list(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto end = std::min(text.find(',', start), text.size());
    if (end > start) {
      out.push_back(text.substr(start, end - start));
    }
    start = end + 1;
  }
  return out;
}

int domain_id_named(const std::string& text, const std::string& where) {
  char* end = nullptr;
  const long id = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || id < 0 || id > kMaxDomainId) {
    throw std::invalid_argument(where + ": must be an integer in " + domain_id_range() + ", got '" +
                                text + "'");
  }
  return static_cast<int>(id);
}

void apply(const JoinOverrides& overrides, ParticipantOptions& options) {
  if (overrides.domain_id) {
    options.domain_id = *overrides.domain_id;
  }
  if (overrides.qos_file) {
    options.qos_file = *overrides.qos_file;
  }
  if (overrides.peers) {
    options.network.peers = *overrides.peers;
  }
  if (overrides.interfaces) {
    options.network.interfaces = *overrides.interfaces;
  }
  if (overrides.discovery_server) {
    options.network.discovery_server = *overrides.discovery_server;
  }
  // A server or peers named in this layer are what the user wants to reach;
  // an interface allow-list fits every mode, so it only leaves localhost.
  if (overrides.discovery) {
    options.discovery = *overrides.discovery;
  } else if (overrides.discovery_server) {
    options.discovery = Discovery::server;
  } else if (overrides.peers) {
    options.discovery = Discovery::peers;
  } else if (overrides.interfaces && options.discovery == Discovery::localhost) {
    options.discovery = Discovery::multicast;
  }
  if (overrides.security_directory) {
    options.security.directory = *overrides.security_directory;
  }
  if (overrides.identity) {
    options.security.identity = *overrides.identity;
  }
}

JoinOverrides overrides_from_environment() {
  JoinOverrides overrides;
  if (auto value = variable("WBI_DOMAIN_ID")) {
    overrides.domain_id = domain_id_named(*value, "WBI_DOMAIN_ID");
  }
  overrides.qos_file = variable("WBI_QOS_FILE");
  if (auto value = variable("WBI_DDS_DISCOVERY")) {
    overrides.discovery = discovery_named(*value, "WBI_DDS_DISCOVERY");
  }
  if (auto value = variable("WBI_DDS_PEERS")) {
    overrides.peers = comma_list(*value);
  }
  if (auto value = variable("WBI_DDS_INTERFACES")) {
    overrides.interfaces = comma_list(*value);
  }
  overrides.discovery_server = variable("WBI_DDS_DISCOVERY_SERVER");
  overrides.security_directory = variable("WBI_DDS_SECURITY_DIRECTORY");
  overrides.identity = variable("WBI_DDS_SECURITY_IDENTITY");
  return overrides;
}

void apply_environment(ParticipantOptions& options) {
  apply(overrides_from_environment(), options);
}

}  // namespace wbi::dds
