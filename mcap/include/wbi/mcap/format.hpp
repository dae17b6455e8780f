// MCAP file format: the records that wbi reads and writes, and the error a
// reader raises on a malformed file. Written from the MCAP specification
// (https://mcap.dev/spec), format version 0.
//
// A file is
//   <magic> <Header> <data section> <DataEnd> [<summary section>] [<summary offset section>]
//   <Footer> <magic>
// Every record is: opcode (uint8), content length (uint64), content. All
// integers are little-endian; a string is a uint32 byte length and UTF-8 bytes;
// a map is a uint32 byte length and its key/value entries.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace wbi::mcap {

// "\x89MCAP0\r\n": the first and the last 8 bytes of every file.
inline constexpr std::array<std::uint8_t, 8> kMagic{0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

// Record opcodes of the specification. 0x00 is reserved (an error here);
// 0x80-0xFF are user opcodes and, like other unknown opcodes, are skipped.
enum class Opcode : std::uint8_t {
  header = 0x01,
  footer = 0x02,
  schema = 0x03,
  channel = 0x04,
  message = 0x05,
  chunk = 0x06,
  message_index = 0x07,
  chunk_index = 0x08,
  attachment = 0x09,
  attachment_index = 0x0A,
  statistics = 0x0B,
  metadata = 0x0C,
  metadata_index = 0x0D,
  summary_offset = 0x0E,
  data_end = 0x0F,
};

// Name of an opcode for messages ("Chunk", "opcode 0x42").
std::string opcode_name(std::uint8_t opcode);

// Chunk compression. The strings in the file are "", "lz4" (LZ4 frame format)
// and "zstd".
enum class Compression { none, lz4, zstd };

const char* compression_name(Compression compression);   // "none", "lz4", "zstd"
const char* compression_field(Compression compression);  // "", "lz4", "zstd": as in the file

using KeyValues = std::map<std::string, std::string>;

// A message type. id 0 is reserved ("no schema").
struct Schema {
  std::uint16_t id = 0;
  std::string name;                // e.g. "wbi::msg::JointState"
  std::string encoding;            // e.g. "omgidl"
  std::vector<std::uint8_t> data;  // e.g. the type's self-contained IDL text
};

// A topic. schema_id 0: the channel has no schema.
struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  // e.g. "cdr"
  KeyValues metadata;            // e.g. the writer's QoS
};

// Counts of the whole file (the Statistics record). Times are log times in ns.
struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time = 0;  // 0 when there are no messages
  std::uint64_t message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

// Where a chunk is and what it holds (the ChunkIndex record, or the same facts
// found by scanning the data section).
struct ChunkInfo {
  std::uint64_t offset = 0;  // of the Chunk record's opcode, from the file start
  std::uint64_t length = 0;  // of the whole Chunk record (opcode and length included)
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::string compression;  // as in the file: "", "lz4", "zstd"
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
};

// A malformed file: the message names the file and the byte offset, e.g.
// "run.mcap: byte 1234: Chunk record: CRC mismatch (stored 0x1234abcd, computed 0x0badf00d)".
class FormatError : public std::runtime_error {
 public:
  FormatError(const std::filesystem::path& file, std::uint64_t offset, const std::string& what);
  const std::filesystem::path& file() const { return file_; }
  std::uint64_t offset() const { return offset_; }

 private:
  std::filesystem::path file_;
  std::uint64_t offset_;
};

}  // namespace wbi::mcap
