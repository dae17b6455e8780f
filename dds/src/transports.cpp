#include "transports.hpp"

#include "wbi/dds/domain_id.hpp"

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <random>
#include <stdexcept>
#include <string>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

namespace wbi::dds::detail {

using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

LocalTransport local_transport_from_environment() {
  const char* text = std::getenv("WBI_DDS_TRANSPORT");
  if (text == nullptr || *text == '\0' || std::string(text) == "udp") {
    return LocalTransport::udp;
  }
  if (std::string(text) == "shm") {
    return LocalTransport::shared_memory;
  }
  throw std::invalid_argument(std::string("WBI_DDS_TRANSPORT must be 'udp' or 'shm', got '") +
                              text + "'");
}

namespace {

constexpr std::uint32_t kSharedMemorySegmentBytes = 4u << 20;

// Fast DDS 2.9 names a participant's shared-memory port by its user-data port
// number, and a peer keeps the port it opened for a number forever. A
// participant that reuses the number of one that is gone (a restarted server, a
// participant created after another was deleted: the well-known port formula
// gives them the same number) gets a new segment under the old name, and its
// peers keep writing into the dead one: every sample lost, for good (fixed in
// later Fast DDS releases by remapping stale ports). A random user-data port
// per participant keeps numbers from being reused; discovery keeps the
// well-known ports. Odd offsets, like the default user port, never take a
// discovery port (those are even).
void use_random_user_port(eprosima::fastdds::dds::DomainParticipantQos& qos, int domain_id) {
  auto& port = qos.wire_protocol().port;
  const int first = port.portBase + port.domainIDGain * domain_id + port.offsetd3;
  const int last = 65535 - port.participantIDGain * kInitialPeersPerAddress;
  const int slots = (last - first) / 2;
  if (slots <= 1) {
    return;  // no room above this domain's ports: keep the default
  }
  static std::mutex mutex;
  static std::mt19937 random(std::random_device{}());
  std::lock_guard lock(mutex);
  const int slot = std::uniform_int_distribution<int>(0, slots - 1)(random);
  port.offsetd3 = static_cast<std::uint16_t>(port.offsetd3 + 2 * slot);
}

}  // namespace

void use_loopback_transports(eprosima::fastdds::dds::DomainParticipantQos& qos, int domain_id,
                             LocalTransport transport) {
  auto& transports = qos.transport();
  transports.use_builtin_transports = false;
  if (transport == LocalTransport::shared_memory) {
    use_random_user_port(qos, domain_id);
    // Fast DDS sends to a peer on the same host through shared memory when both
    // announce a shared-memory locator, and falls back to UDP otherwise.
    auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
    // The default 512 KiB recycled buffers that a busy reader had not read yet
    // ("Buffer is being invalidated"): a lost sample, resent a heartbeat later.
    shm->segment_size(kSharedMemorySegmentBytes);
    transports.user_transports.push_back(shm);
  }
  // No shared-memory transport otherwise: it would only leave a segment in
  // /dev/shm behind every killed process.
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back("127.0.0.1");
  udp->maxInitialPeersRange = kInitialPeersPerAddress;
  transports.user_transports.push_back(udp);

  // Discovery: unicast to 127.0.0.1 only. With a unicast metatraffic locator
  // and initial peers set, Fast DDS sends no multicast.
  Locator_t loopback;
  loopback.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(loopback, 127, 0, 0, 1);
  auto& wire = qos.wire_protocol();
  wire.builtin.initialPeersList.push_back(loopback);
  wire.builtin.metatrafficUnicastLocatorList.push_back(loopback);
  // User data: default_unicast_locator_list stays empty, so that every transport
  // announces its own default locators (the shared-memory port, and UDP on the
  // whitelisted 127.0.0.1). Listing the UDP loopback locator there, as wbi did
  // before, silently sent all user data over UDP even with shared memory on.
}

}  // namespace wbi::dds::detail
