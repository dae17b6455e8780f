#include "discovery.hpp"

#include "wbi/dds/domain_id.hpp"

#include <arpa/inet.h>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

namespace wbi::dds::detail {

using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

namespace {

// "a.b.c.d" or "a.b.c.d:port" as a UDPv4 locator; port 0 when none is given
// (Fast DDS then uses the domain's well-known discovery ports).
Locator_t udp_locator(const std::string& text, const char* what) {
  std::string address = text;
  std::uint32_t port = 0;
  if (const auto colon = text.rfind(':'); colon != std::string::npos) {
    address = text.substr(0, colon);
    const std::string digits = text.substr(colon + 1);
    char* end = nullptr;
    const unsigned long value = std::strtoul(digits.c_str(), &end, 10);
    if (digits.empty() || *end != '\0' || value == 0 || value > 65535) {
      throw std::invalid_argument(std::string(what) + ": bad port in '" + text + "'");
    }
    port = static_cast<std::uint32_t>(value);
  }
  in_addr parsed{};
  if (inet_pton(AF_INET, address.c_str(), &parsed) != 1) {
    throw std::invalid_argument(std::string(what) + ": '" + text +
                                "' is not an IPv4 address (a.b.c.d or a.b.c.d:port)");
  }
  Locator_t locator;
  locator.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(locator, address);
  locator.port = port;
  return locator;
}

}  // namespace

void use_network_transports(eprosima::fastdds::dds::DomainParticipantQos& qos, Discovery discovery,
                            const NetworkOptions& network) {
  auto& transports = qos.transport();
  transports.use_builtin_transports = false;
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->maxInitialPeersRange = kInitialPeersPerAddress;
  for (const auto& address : network.interfaces) {
    (void)udp_locator(address, "network interfaces");  // validates
    udp->interfaceWhiteList.push_back(address);
  }
  // Fast DDS sends to a peer on this host through 127.0.0.1 whenever its own
  // allow-list (or lack of one, as with `fastdds discovery`) permits loopback;
  // a participant that did not listen there would never hear them.
  if (!udp->interfaceWhiteList.empty()) {
    udp->interfaceWhiteList.emplace_back("127.0.0.1");
  }
  transports.user_transports.push_back(udp);

  auto& builtin = qos.wire_protocol().builtin;
  for (const auto& peer : network.peers) {
    builtin.initialPeersList.push_back(udp_locator(peer, "network peers"));
  }
  switch (discovery) {
    case Discovery::localhost:  // not ours: transports.hpp
    case Discovery::multicast:
      break;  // SPDP multicast (239.255.0.1), plus any initial peers
    case Discovery::peers: {
      if (network.peers.empty()) {
        throw std::invalid_argument("network discovery 'peers' needs at least one peer address");
      }
      // A unicast discovery locator and no multicast one: Fast DDS then neither
      // listens on nor sends to the multicast group. 0.0.0.0 stands for every
      // allowed interface; port 0 for the domain's well-known port.
      Locator_t any;
      any.kind = LOCATOR_KIND_UDPv4;
      IPLocator::setIPv4(any, 0, 0, 0, 0);
      builtin.metatrafficUnicastLocatorList.push_back(any);
      break;
    }
    case Discovery::server: {
      if (network.discovery_server.empty()) {
        throw std::invalid_argument("network discovery 'server' needs the server's address:port");
      }
      // The prefix `fastdds discovery -i 0` gives its server.
      eprosima::fastdds::rtps::RemoteServerAttributes server;
      server.ReadguidPrefix(eprosima::fastdds::rtps::DEFAULT_ROS2_SERVER_GUIDPREFIX);
      Locator_t locator = udp_locator(network.discovery_server, "network discovery_server");
      if (locator.port == 0) {
        locator.port = eprosima::fastdds::rtps::DEFAULT_ROS2_SERVER_PORT;
      }
      server.metatrafficUnicastLocatorList.push_back(locator);
      builtin.discovery_config.discoveryProtocol =
          eprosima::fastrtps::rtps::DiscoveryProtocol_t::SUPER_CLIENT;
      builtin.discovery_config.m_DiscoveryServers.push_back(server);
      break;
    }
  }
}

}  // namespace wbi::dds::detail
