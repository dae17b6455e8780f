#include "wbi/mcap/format.hpp"

#include <array>
#include <cstdio>

namespace wbi::mcap {

std::string opcode_name(std::uint8_t opcode) {
  static constexpr std::array<const char*, 16> kNames{
      nullptr,    "Header",        "Footer",        "Schema",     "Channel",         "Message",
      "Chunk",    "MessageIndex",  "ChunkIndex",    "Attachment", "AttachmentIndex", "Statistics",
      "Metadata", "MetadataIndex", "SummaryOffset", "DataEnd"};
  if (opcode < kNames.size() && kNames[opcode] != nullptr) {
    return kNames[opcode];
  }
  std::array<char, 16> text{};
  std::snprintf(text.data(), text.size(), "opcode 0x%02x", opcode);
  return text.data();
}

const char* compression_name(Compression compression) {
  switch (compression) {
    case Compression::lz4:
      return "lz4";
    case Compression::zstd:
      return "zstd";
    case Compression::none:
      break;
  }
  return "none";
}

const char* compression_field(Compression compression) {
  return compression == Compression::none ? "" : compression_name(compression);
}

FormatError::FormatError(const std::filesystem::path& file, std::uint64_t offset,
                         const std::string& what)
    : std::runtime_error(file.string() + ": byte " + std::to_string(offset) + ": " + what),
      file_(file),
      offset_(offset) {}

}  // namespace wbi::mcap
