// Private to the MCAP writer: Writer::Impl (the file, its running CRCs, the open
// chunk and what the summary needs) and the record encoders its parts share.
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "byte_buffer.hpp"
#include "codec.hpp"
#include "crc32.hpp"
#include "wbi/mcap/writer.hpp"

namespace wbi::mcap {

namespace detail {

struct ChunkIndexEntry {
  ChunkInfo chunk;
  std::map<std::uint16_t, std::uint64_t>
      message_index_offsets;               // channel id -> MessageIndex offset
  std::uint64_t message_index_length = 0;  // bytes of all MessageIndex records after the chunk
};

struct MetadataIndexEntry {
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
  std::string name;
};

// Which running CRC the bytes written count towards.
enum class Section { data, data_end, summary };

// Schema: id, name, encoding, data (uint32 length). Written in the data section
// when added and again in the summary.
void encode_schema(ByteBuffer& out, const Schema& schema);

// Channel: id, schema id, topic, message encoding, metadata. Likewise.
void encode_channel(ByteBuffer& out, const Channel& channel);

}  // namespace detail

struct Writer::Impl {
  std::filesystem::path path;
  WriterOptions options;
  std::FILE* file = nullptr;
  bool failed = false;  // a write failed: close() only releases the file
  detail::Section section = detail::Section::data;
  std::uint64_t offset = 0;       // bytes written to the file
  std::uint32_t data_crc = 0;     // CRC-32 of the data section so far (magic included)
  std::uint32_t summary_crc = 0;  // CRC-32 from the summary start to the footer's CRC field
  WriterStatistics written;

  std::vector<Schema> schemas;                        // index = id - 1
  std::vector<Channel> channels;                      // index = id - 1
  std::vector<std::uint64_t> channel_message_counts;  // index = channel id (0 unused)
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;

  // The open chunk: its uncompressed Message records, and per channel id the
  // (log_time, offset in the records) of its messages there.
  detail::ByteBuffer chunk_records;
  std::vector<std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_message_index;
  std::vector<std::uint16_t> chunk_channels;  // ids with entries in the open chunk
  std::uint64_t chunk_start_time = 0;
  std::uint64_t chunk_end_time = 0;

  detail::Compressor compressor;
  detail::ByteBuffer compressed;  // reused compression output
  detail::ByteBuffer scratch;     // reused record encoding
  std::vector<detail::ChunkIndexEntry> chunk_indexes;
  std::vector<detail::MetadataIndexEntry> metadata_indexes;

  Impl(std::filesystem::path file_path, WriterOptions writer_options)
      : path(std::move(file_path)),
        options(std::move(writer_options)),
        compressor(options.compression, options.compression_level) {}

  [[noreturn]] void fail(const std::string& what) {
    failed = true;
    throw std::runtime_error(path.string() + ": " + what);
  }

  // Every byte of the file goes through here.
  void write_bytes(std::span<const std::uint8_t> bytes) {
    if (bytes.empty()) {
      return;
    }
    if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) {
      fail(std::string("write failed: ") + std::strerror(errno));
    }
    if (section == detail::Section::data) {
      data_crc = detail::crc32(data_crc, bytes);
    } else if (section == detail::Section::summary) {
      summary_crc = detail::crc32(summary_crc, bytes);
    }
    offset += bytes.size();
    written.file_bytes = offset;
  }

  void write_scratch() { write_bytes(scratch.span()); }

  void check_open(const char* operation) const {
    if (file == nullptr) {
      throw std::logic_error("mcap::Writer::" + std::string(operation) + " after close() (" +
                             path.string() + ")");
    }
    if (failed) {
      throw std::runtime_error(path.string() + ": " + operation + " after a failed write");
    }
  }

  // The open chunk, then one MessageIndex per channel it holds (ascending id).
  void write_chunk();
  void write_summary_and_footer();
};

}  // namespace wbi::mcap
