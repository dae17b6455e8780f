// CRC-32 (ISO-HDLC, as in zlib and PNG: reflected polynomial 0xEDB88320), the
// checksum MCAP uses for chunks, the data section, the summary and attachments.
#pragma once

#include <cstdint>
#include <span>

namespace wbi::mcap::detail {

// Continues a CRC: crc32(crc32(0, a), b) == crc32(0, a followed by b).
std::uint32_t crc32(std::uint32_t crc, std::span<const std::uint8_t> bytes);

}  // namespace wbi::mcap::detail
