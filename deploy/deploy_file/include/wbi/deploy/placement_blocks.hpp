// The placement blocks of a deploy file (or of a wbi_host file): how its
// processes find each other across hosts, and the DDS Security identity each
// one uses.
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
// and their command-line flags on top, so the same file serves on another
// network or with other keys.
#pragma once

#include <array>
#include <string>

#include <yaml-cpp/yaml.h>

#include <wbi/dds/join_options.hpp>
#include <wbi/dds/participant.hpp>

namespace wbi::deploy {

// A file's layer of the join options (dds/join_options.hpp), as written: read
// once, applied per participant (whose identity differs). A network block
// sets `discovery` (multicast without a mode); a security block sets
// `security_directory` (made absolute from the file) and `identity` (when it
// names one).
struct JoinKeys : dds::JoinOverrides {
  std::string security_where;  // "FILE:LINE" of the security block, for its errors
};

// Reads root["network"] and root["security"]. Throws std::runtime_error
// "FILE:LINE: field: what".
JoinKeys read_placement_blocks(const YAML::Node& root, const std::string& file);

// Writes the keys into `options` for the participant named `identity` (the
// security identity when the file names none; recorded even without a
// security block, for a directory given later). Throws "FILE:LINE:
// security.identity: missing (...)" for a secured file when neither names one.
void apply_join_keys(const JoinKeys& keys, const std::string& identity,
                     dds::ParticipantOptions& options);

// Both at once, for a wbi_host file (runtime::PlacementReader).
void read_placement(const YAML::Node& root, const std::string& file, const std::string& identity,
                    dds::ParticipantOptions& options);

// The keys read_placement handles, for the callers' unknown-key checks.
inline constexpr const char* kNetworkKey = "network";
inline constexpr const char* kSecurityKey = "security";
// Every top-level key read_placement reads (a runtime::PlacementReader's keys).
inline constexpr std::array<const char*, 2> kPlacementKeys{kNetworkKey, kSecurityKey};

}  // namespace wbi::deploy
