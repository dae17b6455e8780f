// The range of DDS domain ids wbi accepts, checked wherever one is read (a
// participant's options, WBI_DOMAIN_ID, --domain, a deploy or host file).
#pragma once

#include <string>

namespace wbi::dds {

// Participant numbers a participant tries at each initial peer's address
// (Fast DDS's maxInitialPeersRange, default 4): up to 64 wbi processes on one
// host find each other without multicast.
inline constexpr int kInitialPeersPerAddress = 64;

// Fast DDS's well-known ports are 7400 + 250 × domain + 10 or 11 + 2 ×
// participant. Past 65535 for the last initial peer, Fast DDS 2.9 ends the
// process (exit 1) while creating the participant: on domain 232 it did.
inline constexpr int kMaxDomainId = (65535 - 7400 - 11 - 2 * (kInitialPeersPerAddress - 1)) / 250;
static_assert(kMaxDomainId == 231);

// "[0, 231]", as error messages name the range.
inline std::string domain_id_range() { return "[0, " + std::to_string(kMaxDomainId) + "]"; }

}  // namespace wbi::dds
