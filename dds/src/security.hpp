// Internal: the DDS Security plugins and their files on a participant's QoS.
#pragma once

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "wbi/dds/network_options.hpp"

namespace wbi::dds::detail {

// Adds the PKI-DH, Access-Permissions and AES-GCM-GMAC plugin properties for
// `security.identity`. Throws std::invalid_argument naming a missing file.
void use_security(eprosima::fastdds::dds::DomainParticipantQos& qos,
                  const SecurityOptions& security);

}  // namespace wbi::dds::detail
