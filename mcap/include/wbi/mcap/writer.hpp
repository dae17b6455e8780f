// Writes an MCAP file: chunked, indexed, with a summary section.
//
// Layout written (see format.hpp):
//   magic, Header{profile, library}
//   data section: Schema and Channel records (outside chunks, written when added),
//                 then each Chunk followed by one MessageIndex per channel it holds
//   DataEnd{CRC-32 of every byte before it, magic included}
//   summary: Schemas, Channels, Statistics, ChunkIndexes (and MetadataIndexes)
//   summary offsets: one SummaryOffset per group
//   Footer{summary start, summary offset start, summary CRC}, magic
//
// Durability: flush() closes the open chunk (Chunk and its MessageIndexes are
// written) and fflush()es, so a process killed after flush() leaves a file whose
// data section is readable up to that point by a reader that tolerates a
// missing summary (wbi::mcap::Reader does).
//
// Cost: write() copies the payload into the chunk buffer and appends one
// message-index entry; both buffers keep their capacity from chunk to chunk, so
// after the first chunk write() does not allocate (a payload larger than the
// chunk size grows the buffer once). Compression and CRCs run once per chunk.
//
// Not thread-safe: one thread writes (a recorder serialises its callbacks).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "wbi/mcap/format.hpp"

namespace wbi::mcap {

struct WriterOptions {
  std::string profile = "wbi";           // Header.profile
  std::string library = "wbi-mcap 0.1";  // Header.library
  // A chunk is closed when its uncompressed records reach this many bytes.
  std::size_t chunk_size = 1024 * 1024;
  Compression compression = Compression::zstd;
  // 0: the codec's fast default (zstd level 1; lz4 fast mode). zstd: 1..19; lz4: 1..12 (HC).
  int compression_level = 0;
};

// What has been written so far.
struct WriterStatistics {
  std::uint64_t messages = 0;
  std::uint64_t payload_bytes = 0;  // sum of message data sizes
  std::uint64_t file_bytes = 0;     // bytes handed to the file so far (after compression)
  std::uint32_t chunks = 0;         // chunks written so far
};

class Writer {
 public:
  // Creates (truncates) the file and writes the magic and the Header.
  // Throws std::runtime_error naming the file when it cannot be opened or written.
  explicit Writer(const std::filesystem::path& path, WriterOptions options = {});
  // Closes the file if close() was not called; errors are then swallowed
  // (call close() to see them).
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;
  // A moved-from writer may only be destroyed. (No move assignment: it would
  // have to close the assigned-to file; hold writers in std::optional to
  // replace one, e.g. when splitting a recording.)
  Writer(Writer&&) noexcept;
  Writer& operator=(Writer&&) = delete;

  // Adds a Schema; returns its id (1, 2, ...). Adding a schema equal in name,
  // encoding and data to an earlier one returns the earlier id, so a recorder
  // may call this once per topic and still writes one Schema per type.
  std::uint16_t add_schema(std::string_view name, std::string_view encoding,
                           std::span<const std::uint8_t> data);
  // The common case: encoding "omgidl", data = the type's self-contained IDL text.
  std::uint16_t add_schema(std::string_view name, std::string_view idl_text) {
    return add_schema(name, "omgidl",
                      {reinterpret_cast<const std::uint8_t*>(idl_text.data()), idl_text.size()});
  }

  // Adds a Channel; returns its id (1, 2, ...). schema_id: from add_schema, or 0
  // for none. Throws std::invalid_argument for an unknown schema id.
  std::uint16_t add_channel(std::uint16_t schema_id, std::string_view topic,
                            std::string_view message_encoding = "cdr",
                            const KeyValues& metadata = {});

  // Appends a message to the open chunk. Times in ns; log_time: when it was
  // received, publish_time: the source stamp. Throws std::invalid_argument for
  // an unknown channel id, std::runtime_error when the file cannot be written.
  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
             std::uint64_t publish_time, std::span<const std::uint8_t> data);

  // Writes a Metadata record (outside chunks), indexed in the summary.
  void write_metadata(std::string_view name, const KeyValues& metadata);

  // Closes the open chunk and hands everything to the operating system (fflush).
  void flush();

  // Writes the open chunk, DataEnd, the summary, the Footer and the magic, and
  // closes the file. Idempotent.
  void close();

  const WriterStatistics& statistics() const;
  const std::filesystem::path& path() const;

 private:
  struct Impl;  // the file, the open chunk and what the summary needs (writer_impl.hpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::mcap
