// Internal: which transports a participant uses, and on which addresses.
#pragma once

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

namespace wbi::dds::detail {

// User data between processes on one host (discovery always goes over UDP on 127.0.0.1).
// See the "latency" section of dds/README.md for why UDP is the default.
enum class LocalTransport {
  udp,            // UDP on 127.0.0.1 (the default)
  shared_memory,  // shared memory, and UDP on 127.0.0.1 to peers that cannot use it
};

// WBI_DDS_TRANSPORT: unset or "udp", or "shm". Throws std::invalid_argument otherwise.
LocalTransport local_transport_from_environment();

// Loopback-only transports: nothing is sent to or received from another address.
void use_loopback_transports(eprosima::fastdds::dds::DomainParticipantQos& qos, int domain_id,
                             LocalTransport transport);

}  // namespace wbi::dds::detail
