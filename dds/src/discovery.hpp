// Internal: transports and discovery for participants on several hosts.
#pragma once

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "wbi/dds/participant.hpp"

namespace wbi::dds::detail {

// UDPv4 only (no shared memory and no data sharing can cross hosts; Fast DDS
// would otherwise use shared memory between network namespaces of one
// machine), on the allowed interfaces, with the discovery mode's locators.
// Throws std::invalid_argument naming a malformed address.
// Discovery::localhost is not handled here (transports.hpp).
void use_network_transports(eprosima::fastdds::dds::DomainParticipantQos& qos, Discovery discovery,
                            const NetworkOptions& network);

}  // namespace wbi::dds::detail
