// The 16-byte RTPS GUID of an endpoint (participant prefix, then entity id).
#pragma once

#include <array>
#include <cstdint>

namespace wbi::dds::detail {

using Guid = std::array<std::uint8_t, 16>;
inline constexpr std::size_t kGuidPrefixSize = 12;  // the participant's part

}  // namespace wbi::dds::detail
