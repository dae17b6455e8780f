// Slicing-by-8 CRC-32: eight 256-entry tables let the loop fold eight input
// bytes per step (Kounavis and Berry, "A Systematic Approach to Building High
// Performance Software-Based CRC Generators", ISCC 2005).
#include "crc32.hpp"

#include <array>

namespace wbi::mcap::detail {

namespace {

constexpr std::uint32_t kPolynomial = 0xEDB88320u;  // reflected 0x04C11DB7

using Tables = std::array<std::array<std::uint32_t, 256>, 8>;

constexpr Tables make_tables() {
  Tables table{};
  // T[0][b]: CRC of the single byte b (bitwise long division).
  for (std::uint32_t b = 0; b < 256; ++b) {
    std::uint32_t c = b;
    for (int bit = 0; bit < 8; ++bit) {
      c = (c & 1u) != 0 ? (c >> 1) ^ kPolynomial : c >> 1;
    }
    table[0][b] = c;
  }
  // T[k][b]: b followed by k zero bytes.
  for (std::size_t k = 1; k < 8; ++k) {
    for (std::uint32_t b = 0; b < 256; ++b) {
      const std::uint32_t prev = table[k - 1][b];
      table[k][b] = (prev >> 8) ^ table[0][prev & 0xFFu];
    }
  }
  return table;
}

constexpr Tables kTable = make_tables();

std::uint32_t load32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

}  // namespace

std::uint32_t crc32(std::uint32_t crc, std::span<const std::uint8_t> bytes) {
  std::uint32_t c = ~crc;
  const std::uint8_t* p = bytes.data();
  std::size_t n = bytes.size();
  // Eight bytes per step: the low word is xored into the state, the high word
  // is looked up as is; each byte's table accounts for the bytes after it.
  while (n >= 8) {
    const std::uint32_t lo = c ^ load32(p);
    const std::uint32_t hi = load32(p + 4);
    c = kTable[7][lo & 0xFFu] ^ kTable[6][(lo >> 8) & 0xFFu] ^ kTable[5][(lo >> 16) & 0xFFu] ^
        kTable[4][lo >> 24] ^ kTable[3][hi & 0xFFu] ^ kTable[2][(hi >> 8) & 0xFFu] ^
        kTable[1][(hi >> 16) & 0xFFu] ^ kTable[0][hi >> 24];
    p += 8;
    n -= 8;
  }
  // The tail, one byte per step.
  for (; n > 0; --n, ++p) {
    c = (c >> 8) ^ kTable[0][(c ^ *p) & 0xFFu];
  }
  return ~c;
}

}  // namespace wbi::mcap::detail
