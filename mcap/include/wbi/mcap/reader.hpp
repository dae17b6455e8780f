// Reads an MCAP file: its summary (fast) and its messages, in log-time or file order.
//
// Opening: the file is memory-mapped. When it ends with a valid Footer and magic
// and has a summary section with Statistics, the summary is used (the data
// section is not read; its chunks are checked as messages are read). Otherwise
// the data section is scanned record by record, decompressing every chunk.
//
// Truncated files (a recorder killed mid-write): the scan stops at the last
// complete record; everything before it is read and info().warnings says where
// the file was cut (info().truncation: where, and what was lost). A file that
// is only a prefix of the magic is an empty, truncated file.
//
// Corrupt files throw FormatError naming the file and the byte offset: bad
// magic, a record length that is malformed or runs past the end of a complete
// file, a CRC mismatch (chunk, data section, summary), a message on an unknown
// channel, a chunk that does not decompress to its stated size.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "wbi/mcap/format.hpp"

namespace wbi::mcap {

struct ReaderOptions {
  // Check chunk CRCs when chunks are decompressed, the data-section CRC when
  // the data section is scanned, and the summary CRC.
  bool validate_crcs = true;
};

// Where a truncated file ends, for a caller that reports what was lost.
struct Truncation {
  std::string description;           // the same text as its entry in FileInfo::warnings
  std::uint64_t readable_bytes = 0;  // every record before this offset was read
  std::string cut_record;            // the record the file ends in, e.g. "Chunk"; empty: none
  std::uint64_t cut_record_offset = 0;
  std::uint64_t cut_record_bytes = 0;  // its declared size, record header included
  // A cut Chunk whose first fields survived: the log times [ns] of its first and
  // last messages, which are all lost (its records are one compressed block).
  bool lost_times_known = false;
  std::uint64_t lost_start_time = 0;
  std::uint64_t lost_end_time = 0;
};

// What a file holds, from its summary or from a scan of its data section.
struct FileInfo {
  std::uint64_t file_size = 0;
  std::string profile;  // Header
  std::string library;
  bool from_summary = false;  // true: read from the summary section, data section not scanned
  bool truncated = false;     // the file ends before its Footer and magic
  Statistics statistics;
  std::map<std::uint16_t, Schema> schemas;
  std::map<std::uint16_t, Channel> channels;
  std::vector<ChunkInfo> chunks;      // in file order
  std::vector<std::string> warnings;  // e.g. where a truncated file was cut
  Truncation truncation;              // when truncated
};

// One message as the reader hands it out. channel and data point into the
// reader; data is valid until the next call to MessageCursor::next().
struct MessageView {
  const Channel* channel = nullptr;
  const Schema* schema = nullptr;  // nullptr when the channel has no schema
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;      // ns
  std::uint64_t publish_time = 0;  // ns
  std::span<const std::uint8_t> data;
};

enum class Order {
  log_time,  // ascending log time; ties in file order
  file,      // the order of the records in the file
};

class Reader;

// Pull-based iteration over the messages. Must not outlive its Reader.
class MessageCursor {
 public:
  ~MessageCursor();
  MessageCursor(MessageCursor&&) noexcept;
  MessageCursor& operator=(MessageCursor&&) noexcept;

  // The next message, or nullptr after the last one. Throws FormatError on a
  // corrupt chunk.
  const MessageView* next();

 private:
  friend class Reader;
  struct State;
  explicit MessageCursor(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

class Reader {
 public:
  // Opens and indexes the file. Throws FormatError for a corrupt file and
  // std::runtime_error naming the file when it cannot be opened.
  explicit Reader(const std::filesystem::path& path, ReaderOptions options = {});
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  // Moving keeps open cursors valid (they refer to the reader's inner state).
  Reader(Reader&&) noexcept;
  Reader& operator=(Reader&&) noexcept;

  const FileInfo& info() const;
  const std::filesystem::path& path() const;

  // All messages in the given order.
  MessageCursor messages(Order order = Order::log_time) const;

  // Full check of a file opened from its summary: data-section CRC, every
  // chunk decompressed with its CRC checked, every record of the data section
  // well-formed and message counts equal to the Statistics. Throws
  // FormatError on the first problem. A scanned file was checked on opening.
  void verify() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::mcap
