// Private to the MCAP reader: record layout constants, the fields of parsed
// records, and Reader::Impl (the mapped file and what opening it found).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "byte_buffer.hpp"
#include "codec.hpp"
#include "mapped_file.hpp"
#include "wbi/mcap/reader.hpp"

namespace wbi::mcap {

namespace detail {

constexpr std::uint64_t kRecordHeader = 1 + 8;           // opcode, length
constexpr std::uint64_t kMessageFields = 2 + 4 + 8 + 8;  // before the payload
constexpr std::uint64_t kFooterRecord = kRecordHeader + 8 + 8 + 4;
constexpr std::uint64_t kFooterCrcCovered =
    kRecordHeader + 8 + 8;  // footer bytes the summary CRC covers
// A chunk claiming more than this uncompressed is treated as corrupt rather
// than allocated.
constexpr std::uint64_t kMaxChunkUncompressed = std::uint64_t{1} << 32;

std::string hex32(std::uint32_t value);

inline std::uint8_t as_byte(Opcode opcode) { return static_cast<std::uint8_t>(opcode); }

// Marks `info` truncated: the warning, and where the file ends for a caller
// that reports what was lost. A record the end falls in is named by its
// opcode (0: none), offset and declared content length.
void mark_truncated(FileInfo& info, std::span<const std::uint8_t> all, std::string description,
                    std::uint64_t readable_bytes, std::uint8_t opcode = 0,
                    std::uint64_t record_offset = 0, std::uint64_t record_length = 0);

// A unit that message iteration loads: a Chunk record, or a Message record
// outside any chunk.
struct Block {
  std::uint64_t offset = 0;  // of the record
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  bool chunk = false;
};

// The fields of a Chunk record before its records.
struct ChunkHeader {
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  std::string compression;
  std::span<const std::uint8_t> records;  // compressed, in the file
};

// Where a record is, for error messages: the record at `offset` in the file, or
// the record at byte *in_chunk of the records of the chunk at `offset`.
struct Where {
  std::uint64_t offset = 0;
  std::optional<std::uint64_t> in_chunk;
};

struct MessageFields {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::span<const std::uint8_t> data;
};

// " (at byte N of the chunk's records)" for a record in a chunk, else "".
std::string where_text(const Where& where);

// The fields of a Message, Schema, Channel and Chunk record's content.
MessageFields message_fields(FieldReader& f);
Schema schema_fields(FieldReader& f);
Channel channel_fields(FieldReader& f);
ChunkHeader chunk_fields(FieldReader& f);

}  // namespace detail

struct Reader::Impl {
  std::filesystem::path path;
  ReaderOptions options;
  detail::MappedFile file;
  FileInfo info;
  std::vector<detail::Block> blocks;  // in file order
  bool complete = false;              // ends with a valid Footer and magic

  Impl(const std::filesystem::path& file_path, ReaderOptions reader_options)
      : path(file_path), options(reader_options), file(file_path) {}

  std::span<const std::uint8_t> bytes() const { return file.bytes(); }

  FormatError error(std::uint64_t offset, const std::string& what) const {
    return FormatError(path, offset, what);
  }

  // Runs parse_fields(FieldReader&) over a record's content; a field that does
  // not fit becomes a FormatError naming where the record is.
  template <typename Parse>
  auto parse(std::uint8_t opcode, std::span<const std::uint8_t> content, detail::Where where,
             Parse&& parse_fields) const {
    detail::FieldReader fields(content);
    try {
      return parse_fields(fields);
    } catch (const detail::ParseError& e) {
      if (where.in_chunk) {
        throw error(where.offset, opcode_name(opcode) + " record at byte " +
                                      std::to_string(*where.in_chunk) +
                                      " of the chunk's records: " + e.what());
      }
      throw error(where.offset + detail::kRecordHeader + e.at(),
                  opcode_name(opcode) + " record: " + e.what());
    }
  }

  void open();
  bool read_summary(std::uint64_t footer_offset);
  void scan(std::uint64_t from, FileInfo& out, std::vector<detail::Block>& out_blocks) const;
  void check_data_crc(std::uint64_t data_end, std::uint32_t stored) const;

  // A chunk's uncompressed records: from the file for uncompressed chunks,
  // else decompressed into buffer. Checks the CRC when asked.
  std::span<const std::uint8_t> chunk_records(std::uint64_t chunk_offset,
                                              const detail::ChunkHeader& chunk,
                                              detail::ByteBuffer& buffer,
                                              detail::Decompressor& decompressor) const;
  // Reads the Chunk record at offset (checked against the file).
  detail::ChunkHeader chunk_at(std::uint64_t offset) const;
  // Calls visit(opcode, content, offset in records) for each record in a chunk.
  template <typename Visit>
  void for_each_chunk_record(std::uint64_t chunk_offset, std::span<const std::uint8_t> records,
                             Visit&& visit) const;

  void add_schema(Schema schema, std::uint64_t offset, FileInfo& out) const;
  void add_channel(Channel channel, std::uint64_t offset, FileInfo& out) const;
};

template <typename Visit>
void Reader::Impl::for_each_chunk_record(std::uint64_t chunk_offset,
                                         std::span<const std::uint8_t> records,
                                         Visit&& visit) const {
  std::uint64_t at = 0;
  while (at < records.size()) {
    const std::uint64_t left = records.size() - at;
    if (left < detail::kRecordHeader) {
      throw error(chunk_offset, "Chunk record: " + std::to_string(left) +
                                    " stray bytes at the end of its records");
    }
    const std::uint8_t opcode = records[at];
    const auto length = detail::load_le<std::uint64_t>(records.data() + at + 1);
    if (length > left - detail::kRecordHeader) {
      throw error(chunk_offset, "Chunk record: the " + opcode_name(opcode) + " record at byte " +
                                    std::to_string(at) + " of its records has length " +
                                    std::to_string(length) + ", past the records' end");
    }
    visit(opcode, records.subspan(at + detail::kRecordHeader, length), at);
    at += detail::kRecordHeader + length;
  }
}

}  // namespace wbi::mcap
