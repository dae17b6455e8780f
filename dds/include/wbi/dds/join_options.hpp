// How a process joins a deployment: the settings of ParticipantOptions that a
// user gives by name, in rising precedence
//   defaults < deploy file (wbi/deploy/placement.hpp) < WBI_* environment < command-line flags.
// Every tool and host applies them in that order (dds/README.md, "Joining a
// deployment", lists every variable and flag).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "wbi/dds/participant.hpp"

namespace wbi::dds {

// Settings given by name; unset ones leave the options as they are.
struct JoinOverrides {
  std::optional<int> domain_id;
  std::optional<Discovery> discovery;
  std::optional<std::vector<std::string>> peers;
  std::optional<std::vector<std::string>> interfaces;
  std::optional<std::string> discovery_server;
  std::optional<std::string> qos_file;
  std::optional<std::string> security_directory;
  std::optional<std::string> identity;
};

// Applies `overrides` to `options`. Without an explicit discovery mode in the
// same overrides, the addresses given imply one: a discovery server -> server,
// peers -> peers, interfaces -> multicast (only when the options are localhost:
// an allow-list fits every mode).
void apply(const JoinOverrides& overrides, ParticipantOptions& options);

// WBI_DOMAIN_ID, WBI_QOS_FILE, WBI_DDS_DISCOVERY, WBI_DDS_PEERS,
// WBI_DDS_INTERFACES (comma-separated), WBI_DDS_DISCOVERY_SERVER,
// WBI_DDS_SECURITY_DIRECTORY, WBI_DDS_SECURITY_IDENTITY; empty ones count as
// unset. Throws std::invalid_argument naming the variable on a bad value.
JoinOverrides overrides_from_environment();

// apply(overrides_from_environment(), options).
void apply_environment(ParticipantOptions& options);

// "localhost" | "multicast" | "peers" | "server"; throws std::invalid_argument
// "WHERE: must be localhost, multicast, peers or server, got 'NAME'".
Discovery discovery_named(const std::string& name, const std::string& where);
const char* discovery_name(Discovery discovery);

// "a,b,,c" -> {a, b, c}.
std::vector<std::string> comma_list(const std::string& text);

// A domain id in [0, kMaxDomainId] (domain_id.hpp); throws std::invalid_argument "WHERE: ...".
int domain_id_named(const std::string& text, const std::string& where);

}  // namespace wbi::dds
