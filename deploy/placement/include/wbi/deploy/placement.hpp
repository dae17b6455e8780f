// Host placement in a deploy file (or a wbi_host file): how its processes find
// each other across hosts, and the DDS Security identity each one uses.
//
//   network:                              # optional; without it: this host only
//     discovery: multicast                # localhost | multicast | peers | server
//     peers: [10.77.0.1, 10.77.0.2]       # initial peers ("a.b.c.d[:port]"); needed by peers
//     interfaces: [10.77.0.1, 10.77.0.2]  # allow-list; each host uses the ones it has
//     server: 10.77.0.1:11811             # a `fastdds discovery -i 0` server; needed by server
//   security:                             # optional; without it: no DDS Security
//     directory: secure_demo              # relative to the file; from scripts/wbi-security-setup
//     identity: controller                # default: the process's name
//
// The file is one layer of the join options (dds/README.md, "Joining a
// deployment"): callers apply the WBI_DDS_* environment (dds::apply_environment)
// and their command-line flags on top, so the same deploy file serves on
// another network or with other keys.
#pragma once

#include <array>
#include <string>

#include <yaml-cpp/yaml.h>

#include <wbi/dds/participant.hpp>

namespace wbi::deploy {

// Reads root["network"] and root["security"] into `options` (discovery,
// network, security). `identity` names the participant's identity when the
// security block does not (and is recorded without one, for a security
// directory given later). Throws std::runtime_error "FILE:LINE: field: what".
void read_placement(const YAML::Node& root, const std::string& file, const std::string& identity,
                    dds::ParticipantOptions& options);

// Reads a deploy file: its root map. Throws std::runtime_error "FILE[:LINE]:
// what" when it cannot be read, does not parse, or is not a map.
YAML::Node load_deploy_file(const std::string& file);

// Joins the deployment `file` describes: its domain_id, qos_file (relative to
// it), network and security blocks, on top of `options`. For tools pointed at
// a deploy file (`wbi ... --deploy FILE`). Throws std::runtime_error "FILE:LINE: ...".
void read_join_options(const std::string& file, const std::string& identity,
                       dds::ParticipantOptions& options);

// The keys read_placement handles, for the callers' unknown-key checks.
inline constexpr const char* kNetworkKey = "network";
inline constexpr const char* kSecurityKey = "security";
// Every top-level key read_placement reads (a runtime::PlacementReader's keys).
inline constexpr std::array<const char*, 2> kPlacementKeys{kNetworkKey, kSecurityKey};

}  // namespace wbi::deploy
