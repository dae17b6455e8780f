// Where a participant looks for its peers when they are on other hosts, and
// the DDS Security files it authenticates with. Both default to "off": a
// participant with default options stays on 127.0.0.1 with no security.
#pragma once

#include <string>
#include <vector>

namespace wbi::dds {

// Addresses for Discovery::multicast, Discovery::peers and Discovery::server.
struct NetworkOptions {
  // IPv4 addresses (optionally "address:port") announced to at start-up; with
  // Discovery::peers the only destinations of discovery traffic.
  std::vector<std::string> peers;
  // IPv4 addresses of the local interfaces DDS may use; empty: all of them.
  // Addresses that this host does not have are ignored, so one list can name
  // the interfaces of every host of a deploy.
  std::vector<std::string> interfaces;
  // "address:port" of a Fast DDS discovery server (`fastdds discovery -i 0`),
  // for Discovery::server.
  std::string discovery_server;
};

// DDS Security (PKI-DH authentication, Access-Permissions, AES-GCM-GMAC
// encryption) with the files that scripts/wbi-security-setup writes:
//   DIRECTORY/ca.pem                        identity and permissions CA
//   DIRECTORY/governance.p7s                signed governance document
//   DIRECTORY/IDENTITY/cert.pem, key.pem    the participant's identity
//   DIRECTORY/IDENTITY/permissions.p7s      its signed permissions
struct SecurityOptions {
  std::string directory;  // empty: no security
  std::string identity;
  bool enabled() const { return !directory.empty(); }
};

}  // namespace wbi::dds
