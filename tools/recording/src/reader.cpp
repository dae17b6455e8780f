#include "wbi/mcap/reader.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <tuple>
#include <utility>

#include "byte_buffer.hpp"
#include "codec.hpp"
#include "crc32.hpp"

namespace wbi::mcap {

namespace {

using detail::ByteBuffer;
using detail::FieldReader;
using detail::ParseError;

constexpr std::uint64_t kRecordHeader = 1 + 8;           // opcode, length
constexpr std::uint64_t kMessageFields = 2 + 4 + 8 + 8;  // before the payload
constexpr std::uint64_t kFooterRecord = kRecordHeader + 8 + 8 + 4;
constexpr std::uint64_t kFooterCrcCovered =
    kRecordHeader + 8 + 8;  // footer bytes the summary CRC covers
// A chunk claiming more than this uncompressed is treated as corrupt rather
// than allocated.
constexpr std::uint64_t kMaxChunkUncompressed = std::uint64_t{1} << 32;

std::string hex32(std::uint32_t value) {
  std::array<char, 16> text{};
  std::snprintf(text.data(), text.size(), "0x%08x", value);
  return text.data();
}

std::uint8_t as_byte(Opcode opcode) { return static_cast<std::uint8_t>(opcode); }

// Marks `info` truncated: the warning, and where the file ends for a caller
// that reports what was lost. A record the end falls in is named by its
// opcode (0: none), offset and declared content length.
void mark_truncated(FileInfo& info, std::span<const std::uint8_t> all, std::string description,
                    std::uint64_t readable_bytes, std::uint8_t opcode = 0,
                    std::uint64_t record_offset = 0, std::uint64_t record_length = 0) {
  info.truncated = true;
  info.warnings.push_back(description);
  Truncation& cut = info.truncation;
  cut.description = std::move(description);
  cut.readable_bytes = readable_bytes;
  if (opcode == 0) {
    return;
  }
  cut.cut_record = opcode_name(opcode);
  cut.cut_record_offset = record_offset;
  cut.cut_record_bytes = kRecordHeader + record_length;
  // A Chunk begins with the log times of its first and last messages.
  const std::uint64_t times_end = record_offset + kRecordHeader + 16;
  if (opcode == as_byte(Opcode::chunk) && all.size() >= times_end) {
    cut.lost_times_known = true;
    cut.lost_start_time =
        detail::load_le<std::uint64_t>(all.data() + record_offset + kRecordHeader);
    cut.lost_end_time =
        detail::load_le<std::uint64_t>(all.data() + record_offset + kRecordHeader + 8);
  }
}

// The file, read-only and memory-mapped (nothing mapped for an empty file).
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
      throw std::runtime_error(path.string() + ": cannot open: " + std::strerror(errno));
    }
    struct stat status {};
    if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
      const int error = errno;
      ::close(fd);
      throw std::runtime_error(
          path.string() + ": " +
          (S_ISREG(status.st_mode) ? std::strerror(error) : "not a regular file"));
    }
    size_ = static_cast<std::size_t>(status.st_size);
    if (size_ > 0) {
      void* mapped = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (mapped == MAP_FAILED) {
        const int error = errno;
        ::close(fd);
        throw std::runtime_error(path.string() + ": cannot map: " + std::strerror(error));
      }
      data_ = static_cast<const std::uint8_t*>(mapped);
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_ != nullptr) {
      ::munmap(const_cast<std::uint8_t*>(data_), size_);
    }
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const std::uint8_t> bytes() const { return {data_, size_}; }
  std::uint64_t size() const { return size_; }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

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
std::string where_text(const Where& where) {
  return where.in_chunk
             ? " (at byte " + std::to_string(*where.in_chunk) + " of the chunk's records)"
             : std::string();
}

MessageFields message_fields(FieldReader& f) {
  MessageFields m;
  m.channel_id = f.get<std::uint16_t>("channel_id");
  m.sequence = f.get<std::uint32_t>("sequence");
  m.log_time = f.get<std::uint64_t>("log_time");
  m.publish_time = f.get<std::uint64_t>("publish_time");
  m.data = f.rest();
  return m;
}

Schema schema_fields(FieldReader& f) {
  Schema s;
  s.id = f.get<std::uint16_t>("id");
  s.name = f.string("name");
  s.encoding = f.string("encoding");
  const auto data = f.bytes32("data");
  s.data.assign(data.begin(), data.end());
  return s;
}

Channel channel_fields(FieldReader& f) {
  Channel c;
  c.id = f.get<std::uint16_t>("id");
  c.schema_id = f.get<std::uint16_t>("schema_id");
  c.topic = f.string("topic");
  c.message_encoding = f.string("message_encoding");
  c.metadata = f.key_values("metadata");
  return c;
}

ChunkHeader chunk_fields(FieldReader& f) {
  ChunkHeader c;
  c.start_time = f.get<std::uint64_t>("message_start_time");
  c.end_time = f.get<std::uint64_t>("message_end_time");
  c.uncompressed_size = f.get<std::uint64_t>("uncompressed_size");
  c.uncompressed_crc = f.get<std::uint32_t>("uncompressed_crc");
  c.compression = f.string("compression");
  c.records = f.bytes(f.get<std::uint64_t>("records length"), "records");
  if (f.remaining() != 0) {
    throw ParseError(f.position(), std::to_string(f.remaining()) + " bytes after the records");
  }
  return c;
}

}  // namespace

struct Reader::Impl {
  std::filesystem::path path;
  ReaderOptions options;
  MappedFile file;
  FileInfo info;
  std::vector<Block> blocks;  // in file order
  bool complete = false;      // ends with a valid Footer and magic

  Impl(const std::filesystem::path& file_path, ReaderOptions reader_options)
      : path(file_path), options(reader_options), file(file_path) {}

  std::span<const std::uint8_t> bytes() const { return file.bytes(); }

  FormatError error(std::uint64_t offset, const std::string& what) const {
    return FormatError(path, offset, what);
  }

  // Runs parse_fields(FieldReader&) over a record's content; a field that does
  // not fit becomes a FormatError naming where the record is.
  template <typename Parse>
  auto parse(std::uint8_t opcode, std::span<const std::uint8_t> content, Where where,
             Parse&& parse_fields) const {
    FieldReader fields(content);
    try {
      return parse_fields(fields);
    } catch (const ParseError& e) {
      if (where.in_chunk) {
        throw error(where.offset, opcode_name(opcode) + " record at byte " +
                                      std::to_string(*where.in_chunk) +
                                      " of the chunk's records: " + e.what());
      }
      throw error(where.offset + kRecordHeader + e.at(),
                  opcode_name(opcode) + " record: " + e.what());
    }
  }

  void open();
  bool read_summary(std::uint64_t footer_offset);
  void scan(std::uint64_t from, FileInfo& out, std::vector<Block>& out_blocks) const;
  void check_data_crc(std::uint64_t data_end, std::uint32_t stored) const;

  // A chunk's uncompressed records: from the file for uncompressed chunks,
  // else decompressed into buffer. Checks the CRC when asked.
  std::span<const std::uint8_t> chunk_records(std::uint64_t chunk_offset, const ChunkHeader& chunk,
                                              ByteBuffer& buffer,
                                              detail::Decompressor& decompressor) const;
  // Reads the Chunk record at offset (checked against the file).
  ChunkHeader chunk_at(std::uint64_t offset) const;
  // Calls visit(opcode, content, offset in records) for each record in a chunk.
  template <typename Visit>
  void for_each_chunk_record(std::uint64_t chunk_offset, std::span<const std::uint8_t> records,
                             Visit&& visit) const;

  void add_schema(Schema schema, std::uint64_t offset, FileInfo& out) const;
  void add_channel(Channel channel, std::uint64_t offset, FileInfo& out) const;
};

void Reader::Impl::add_schema(Schema schema, std::uint64_t offset, FileInfo& out) const {
  if (schema.id == 0) {
    throw error(offset, "Schema record: id 0 is reserved");
  }
  const auto [it, added] = out.schemas.try_emplace(schema.id, schema);
  if (!added && (it->second.name != schema.name || it->second.encoding != schema.encoding ||
                 it->second.data != schema.data)) {
    throw error(offset, "Schema record: id " + std::to_string(schema.id) +
                            " was defined before with different content");
  }
}

void Reader::Impl::add_channel(Channel channel, std::uint64_t offset, FileInfo& out) const {
  const auto [it, added] = out.channels.try_emplace(channel.id, channel);
  if (!added && (it->second.topic != channel.topic || it->second.schema_id != channel.schema_id ||
                 it->second.message_encoding != channel.message_encoding)) {
    throw error(offset, "Channel record: id " + std::to_string(channel.id) +
                            " was defined before with different content");
  }
}

ChunkHeader Reader::Impl::chunk_at(std::uint64_t offset) const {
  const auto all = bytes();
  if (offset > all.size() || all.size() - offset < kRecordHeader) {
    throw error(offset, "chunk index points past the end of the file (" +
                            std::to_string(all.size()) + " bytes)");
  }
  const std::uint8_t opcode = all[offset];
  const auto length = detail::load_le<std::uint64_t>(all.data() + offset + 1);
  if (opcode != as_byte(Opcode::chunk)) {
    throw error(offset, "chunk index points to a " + opcode_name(opcode) + " record, not a Chunk");
  }
  if (length > all.size() - offset - kRecordHeader) {
    throw error(offset, "Chunk record length " + std::to_string(length) +
                            " runs past the end of the file (" + std::to_string(all.size()) +
                            " bytes)");
  }
  return parse(opcode, all.subspan(offset + kRecordHeader, length), Where{offset, {}},
               chunk_fields);
}

std::span<const std::uint8_t> Reader::Impl::chunk_records(
    std::uint64_t chunk_offset, const ChunkHeader& chunk, ByteBuffer& buffer,
    detail::Decompressor& decompressor) const {
  std::span<const std::uint8_t> records = chunk.records;
  if (!chunk.compression.empty()) {
    if (chunk.uncompressed_size > kMaxChunkUncompressed) {
      throw error(chunk_offset, "Chunk record: implausible uncompressed size " +
                                    std::to_string(chunk.uncompressed_size));
    }
    try {
      const auto declared = detail::declared_size(chunk.compression, chunk.records);
      if (declared && *declared != chunk.uncompressed_size) {
        throw std::runtime_error(chunk.compression + " frame holds " + std::to_string(*declared) +
                                 " bytes, the chunk says " +
                                 std::to_string(chunk.uncompressed_size));
      }
      buffer.resize(static_cast<std::size_t>(chunk.uncompressed_size));
      decompressor.decompress(chunk.compression, chunk.records, {buffer.data(), buffer.size()});
    } catch (const std::runtime_error& e) {
      throw error(chunk_offset, std::string("Chunk record: cannot decompress: ") + e.what());
    }
    records = buffer.span();
  } else if (chunk.records.size() != chunk.uncompressed_size) {
    throw error(chunk_offset, "Chunk record: uncompressed chunk of " +
                                  std::to_string(chunk.records.size()) + " bytes says " +
                                  std::to_string(chunk.uncompressed_size));
  }
  if (options.validate_crcs && chunk.uncompressed_crc != 0) {
    const std::uint32_t computed = detail::crc32(0, records);
    if (computed != chunk.uncompressed_crc) {
      throw error(chunk_offset, "Chunk record: CRC mismatch (stored " +
                                    hex32(chunk.uncompressed_crc) + ", computed " +
                                    hex32(computed) + ")");
    }
  }
  return records;
}

template <typename Visit>
void Reader::Impl::for_each_chunk_record(std::uint64_t chunk_offset,
                                         std::span<const std::uint8_t> records,
                                         Visit&& visit) const {
  std::uint64_t at = 0;
  while (at < records.size()) {
    const std::uint64_t left = records.size() - at;
    if (left < kRecordHeader) {
      throw error(chunk_offset, "Chunk record: " + std::to_string(left) +
                                    " stray bytes at the end of its records");
    }
    const std::uint8_t opcode = records[at];
    const auto length = detail::load_le<std::uint64_t>(records.data() + at + 1);
    if (length > left - kRecordHeader) {
      throw error(chunk_offset, "Chunk record: the " + opcode_name(opcode) + " record at byte " +
                                    std::to_string(at) + " of its records has length " +
                                    std::to_string(length) + ", past the records' end");
    }
    visit(opcode, records.subspan(at + kRecordHeader, length), at);
    at += kRecordHeader + length;
  }
}

void Reader::Impl::check_data_crc(std::uint64_t data_end, std::uint32_t stored) const {
  if (!options.validate_crcs || stored == 0) {
    return;
  }
  // The reference writers compute it from the first byte (magic included);
  // accept a CRC that starts after the magic too.
  const auto data = bytes().first(data_end);
  const std::uint32_t computed = detail::crc32(0, data);
  if (computed != stored && detail::crc32(0, data.subspan(kMagic.size())) != stored) {
    throw error(data_end, "DataEnd record: data section CRC mismatch (stored " + hex32(stored) +
                              ", computed " + hex32(computed) + ")");
  }
}

// Scans the data section from `from` (just after the Header) record by record,
// decompressing chunks, until DataEnd, a Footer or the end of the file.
void Reader::Impl::scan(std::uint64_t from, FileInfo& out, std::vector<Block>& out_blocks) const {
  const auto all = bytes();
  const std::uint64_t size = all.size();
  Statistics& stats = out.statistics;
  ByteBuffer buffer;
  detail::Decompressor decompressor;

  const auto count_message = [&](const MessageFields& m, Where where) {
    const auto channel = out.channels.find(m.channel_id);
    if (channel == out.channels.end()) {
      throw error(where.offset, "Message record" + where_text(where) + ": unknown channel id " +
                                    std::to_string(m.channel_id));
    }
    if (channel->second.schema_id != 0 && !out.schemas.contains(channel->second.schema_id)) {
      throw error(where.offset, "Message record" + where_text(where) + ": channel " +
                                    std::to_string(m.channel_id) + " has unknown schema id " +
                                    std::to_string(channel->second.schema_id));
    }
    if (stats.message_count == 0) {
      stats.message_start_time = m.log_time;
      stats.message_end_time = m.log_time;
    }
    stats.message_start_time = std::min(stats.message_start_time, m.log_time);
    stats.message_end_time = std::max(stats.message_end_time, m.log_time);
    ++stats.message_count;
    ++stats.channel_message_counts[m.channel_id];
  };

  std::uint64_t pos = from;
  for (;;) {
    if (size - pos < kRecordHeader) {
      mark_truncated(out, all,
                     pos == size
                         ? "file truncated: it ends at byte " + std::to_string(size) +
                               " without a DataEnd record (not closed, e.g. a killed recorder); "
                               "read everything before it"
                         : "file truncated: it ends at byte " + std::to_string(size) +
                               " inside the header of a record that starts at byte " +
                               std::to_string(pos) + "; read everything before it",
                     pos);
      break;
    }
    const std::uint8_t opcode = all[pos];
    const auto length = detail::load_le<std::uint64_t>(all.data() + pos + 1);
    if (opcode == 0) {
      throw error(pos, "invalid opcode 0x00");
    }
    if (length > size - pos - kRecordHeader) {
      if (complete) {
        throw error(pos, opcode_name(opcode) + " record length " + std::to_string(length) +
                             " runs past the end of the file (" + std::to_string(size) + " bytes)");
      }
      mark_truncated(out, all,
                     "file truncated: it ends at byte " + std::to_string(size) + " inside a " +
                         opcode_name(opcode) + " record that starts at byte " +
                         std::to_string(pos) + " (" + std::to_string(length) +
                         " bytes long); read everything before it",
                     pos, opcode, pos, length);
      break;
    }
    const auto content = all.subspan(pos + kRecordHeader, length);
    bool stop = false;
    switch (static_cast<Opcode>(opcode)) {
      case Opcode::header:
        throw error(pos, "a second Header record");
      case Opcode::footer:
        out.warnings.push_back("no DataEnd record before the Footer at byte " +
                               std::to_string(pos));
        stop = true;
        break;
      case Opcode::data_end: {
        const auto crc = parse(opcode, content, Where{pos, {}}, [](FieldReader& f) {
          return f.get<std::uint32_t>("data_section_crc");
        });
        check_data_crc(pos, crc);
        if (!complete) {
          mark_truncated(out, all,
                         "file truncated: it ends at byte " + std::to_string(size) +
                             ", after the DataEnd record at byte " + std::to_string(pos) +
                             " (summary or footer cut off); all messages are there",
                         size);
        }
        stop = true;
        break;
      }
      case Opcode::schema:
        add_schema(parse(opcode, content, Where{pos, {}}, schema_fields), pos, out);
        break;
      case Opcode::channel:
        add_channel(parse(opcode, content, Where{pos, {}}, channel_fields), pos, out);
        break;
      case Opcode::message: {
        const auto m = parse(opcode, content, Where{pos, {}}, message_fields);
        count_message(m, Where{pos, {}});
        out_blocks.push_back({pos, m.log_time, m.log_time, false});
        break;
      }
      case Opcode::chunk: {
        const auto chunk = parse(opcode, content, Where{pos, {}}, chunk_fields);
        const auto records = chunk_records(pos, chunk, buffer, decompressor);
        Block block{pos, 0, 0, true};
        bool any = false;
        for_each_chunk_record(
            pos, records,
            [&](std::uint8_t inner, std::span<const std::uint8_t> body, std::uint64_t at) {
              const Where where{pos, at};
              if (inner == as_byte(Opcode::schema)) {
                add_schema(parse(inner, body, where, schema_fields), pos, out);
              } else if (inner == as_byte(Opcode::channel)) {
                add_channel(parse(inner, body, where, channel_fields), pos, out);
              } else if (inner == as_byte(Opcode::message)) {
                const auto m = parse(inner, body, where, message_fields);
                count_message(m, where);
                block.start_time = any ? std::min(block.start_time, m.log_time) : m.log_time;
                block.end_time = any ? std::max(block.end_time, m.log_time) : m.log_time;
                any = true;
              }
            });
        out_blocks.push_back(block);
        out.chunks.push_back({pos, kRecordHeader + length, chunk.start_time, chunk.end_time,
                              chunk.compression, chunk.records.size(), chunk.uncompressed_size});
        ++stats.chunk_count;
        break;
      }
      case Opcode::attachment:
        ++stats.attachment_count;
        break;
      case Opcode::metadata:
        ++stats.metadata_count;
        break;
      default:
        break;  // indexes (rebuilt here), user and unknown opcodes
    }
    if (stop) {
      break;
    }
    pos += kRecordHeader + length;
  }
  stats.schema_count = static_cast<std::uint16_t>(out.schemas.size());
  stats.channel_count = static_cast<std::uint32_t>(out.channels.size());
}

// Reads the summary section named by the Footer at footer_offset. Returns
// false when it cannot stand in for a scan (no summary, no Statistics, or
// messages without chunk indexes).
bool Reader::Impl::read_summary(std::uint64_t footer_offset) {
  const auto all = bytes();
  struct Footer {
    std::uint64_t summary_start;
    std::uint64_t summary_offset_start;
    std::uint32_t summary_crc;
  };
  const std::uint8_t footer_opcode = all[footer_offset];
  const auto footer_length = detail::load_le<std::uint64_t>(all.data() + footer_offset + 1);
  if (footer_opcode != as_byte(Opcode::footer) || footer_length != kFooterRecord - kRecordHeader) {
    throw error(footer_offset, "bad Footer record before the closing magic (" +
                                   opcode_name(footer_opcode) + ", length " +
                                   std::to_string(footer_length) + ")");
  }
  const auto footer = parse(footer_opcode, all.subspan(footer_offset + kRecordHeader, 20),
                            Where{footer_offset, {}}, [](FieldReader& f) {
                              Footer out{};
                              out.summary_start = f.get<std::uint64_t>("summary_start");
                              out.summary_offset_start =
                                  f.get<std::uint64_t>("summary_offset_start");
                              out.summary_crc = f.get<std::uint32_t>("summary_crc");
                              return out;
                            });
  if (footer.summary_start == 0) {
    return false;
  }
  if (footer.summary_start < kMagic.size() || footer.summary_start > footer_offset) {
    throw error(footer_offset, "Footer record: summary start " +
                                   std::to_string(footer.summary_start) +
                                   " is outside the file's body");
  }
  if (footer.summary_offset_start != 0 && (footer.summary_offset_start < footer.summary_start ||
                                           footer.summary_offset_start > footer_offset)) {
    throw error(footer_offset, "Footer record: summary offset start " +
                                   std::to_string(footer.summary_offset_start) +
                                   " is outside the summary");
  }
  if (options.validate_crcs && footer.summary_crc != 0) {
    const std::uint32_t computed =
        detail::crc32(0, all.subspan(footer.summary_start,
                                     footer_offset + kFooterCrcCovered - footer.summary_start));
    if (computed != footer.summary_crc) {
      throw error(footer.summary_start, "summary section CRC mismatch (stored " +
                                            hex32(footer.summary_crc) + ", computed " +
                                            hex32(computed) + ")");
    }
  }

  FileInfo summary;
  summary.file_size = info.file_size;
  summary.profile = info.profile;
  summary.library = info.library;
  bool has_statistics = false;
  const std::uint64_t end =
      footer.summary_offset_start != 0 ? footer.summary_offset_start : footer_offset;
  std::uint64_t pos = footer.summary_start;
  while (pos < end) {
    if (end - pos < kRecordHeader) {
      throw error(pos, "summary section: a record header is cut off at its end");
    }
    const std::uint8_t opcode = all[pos];
    const auto length = detail::load_le<std::uint64_t>(all.data() + pos + 1);
    if (length > end - pos - kRecordHeader) {
      throw error(pos, opcode_name(opcode) + " record length " + std::to_string(length) +
                           " runs past the end of the summary section (byte " +
                           std::to_string(end) + ")");
    }
    const auto content = all.subspan(pos + kRecordHeader, length);
    switch (static_cast<Opcode>(opcode)) {
      case Opcode::schema:
        add_schema(parse(opcode, content, Where{pos, {}}, schema_fields), pos, summary);
        break;
      case Opcode::channel:
        add_channel(parse(opcode, content, Where{pos, {}}, channel_fields), pos, summary);
        break;
      case Opcode::statistics:
        summary.statistics = parse(opcode, content, Where{pos, {}}, [](FieldReader& f) {
          Statistics s;
          s.message_count = f.get<std::uint64_t>("message_count");
          s.schema_count = f.get<std::uint16_t>("schema_count");
          s.channel_count = f.get<std::uint32_t>("channel_count");
          s.attachment_count = f.get<std::uint32_t>("attachment_count");
          s.metadata_count = f.get<std::uint32_t>("metadata_count");
          s.chunk_count = f.get<std::uint32_t>("chunk_count");
          s.message_start_time = f.get<std::uint64_t>("message_start_time");
          s.message_end_time = f.get<std::uint64_t>("message_end_time");
          s.channel_message_counts = f.id_counts("channel_message_counts");
          return s;
        });
        has_statistics = true;
        break;
      case Opcode::chunk_index: {
        auto chunk = parse(opcode, content, Where{pos, {}}, [](FieldReader& f) {
          ChunkInfo c;
          c.message_start_time = f.get<std::uint64_t>("message_start_time");
          c.message_end_time = f.get<std::uint64_t>("message_end_time");
          c.offset = f.get<std::uint64_t>("chunk_start_offset");
          c.length = f.get<std::uint64_t>("chunk_length");
          f.id_counts("message_index_offsets");
          f.get<std::uint64_t>("message_index_length");
          c.compression = f.string("compression");
          c.compressed_size = f.get<std::uint64_t>("compressed_size");
          c.uncompressed_size = f.get<std::uint64_t>("uncompressed_size");
          return c;
        });
        if (chunk.offset < kMagic.size() || chunk.offset > footer.summary_start ||
            chunk.length < kRecordHeader || chunk.length > footer.summary_start - chunk.offset) {
          throw error(pos, "ChunkIndex record: chunk at byte " + std::to_string(chunk.offset) +
                               " (" + std::to_string(chunk.length) +
                               " bytes) is outside the data section");
        }
        // One cheap look per chunk: the indexed record is a Chunk of that length.
        const std::uint8_t chunk_opcode = all[chunk.offset];
        const auto chunk_length = detail::load_le<std::uint64_t>(all.data() + chunk.offset + 1);
        if (chunk_opcode != as_byte(Opcode::chunk) ||
            chunk_length != chunk.length - kRecordHeader) {
          throw error(chunk.offset, "expected the Chunk record of " + std::to_string(chunk.length) +
                                        " bytes that the ChunkIndex at byte " +
                                        std::to_string(pos) + " names, found a " +
                                        opcode_name(chunk_opcode) + " record of length " +
                                        std::to_string(chunk_length));
        }
        summary.chunks.push_back(std::move(chunk));
        break;
      }
      default:
        break;  // attachment and metadata indexes, offsets: counted in Statistics
    }
    pos += kRecordHeader + length;
  }
  for (const auto& [id, channel] : summary.channels) {
    if (channel.schema_id != 0 && !summary.schemas.contains(channel.schema_id)) {
      throw error(footer.summary_start, "summary: channel " + std::to_string(id) +
                                            " has unknown schema id " +
                                            std::to_string(channel.schema_id));
    }
  }
  if (!has_statistics || (summary.statistics.message_count > 0 && summary.chunks.empty())) {
    return false;
  }
  std::sort(summary.chunks.begin(), summary.chunks.end(),
            [](const ChunkInfo& a, const ChunkInfo& b) { return a.offset < b.offset; });
  blocks.clear();
  for (const auto& chunk : summary.chunks) {
    blocks.push_back({chunk.offset, chunk.message_start_time, chunk.message_end_time, true});
  }
  summary.from_summary = true;
  info = std::move(summary);
  return true;
}

void Reader::Impl::open() {
  const auto all = bytes();
  info.file_size = all.size();
  // Leading magic; a file that is only a prefix of it is empty and truncated.
  const std::size_t magic_bytes = std::min<std::size_t>(all.size(), kMagic.size());
  if (!std::equal(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(magic_bytes),
                  kMagic.begin())) {
    throw error(0, "not an MCAP file (bad magic)");
  }
  if (all.size() < kMagic.size()) {
    mark_truncated(info, all,
                   "file truncated: " + std::to_string(all.size()) +
                       " bytes, inside the leading magic; no messages",
                   0);
    return;
  }
  // A complete file ends with Footer and magic.
  complete = all.size() >= 2 * kMagic.size() + kFooterRecord &&
             std::equal(kMagic.begin(), kMagic.end(),
                        all.end() - static_cast<std::ptrdiff_t>(kMagic.size()));
  const std::uint64_t footer_offset = all.size() - kMagic.size() - kFooterRecord;

  // Header: profile, library.
  std::uint64_t pos = kMagic.size();
  if (all.size() - pos < kRecordHeader) {
    mark_truncated(info, all,
                   "file truncated: it ends at byte " + std::to_string(all.size()) +
                       " inside the Header record; no messages",
                   pos);
    return;
  }
  const std::uint8_t opcode = all[pos];
  const auto length = detail::load_le<std::uint64_t>(all.data() + pos + 1);
  if (opcode != as_byte(Opcode::header)) {
    throw error(pos, "the first record is a " + opcode_name(opcode) + ", not a Header");
  }
  if (length > all.size() - pos - kRecordHeader) {
    if (complete) {
      throw error(
          pos, "Header record length " + std::to_string(length) + " runs past the end of the file");
    }
    mark_truncated(info, all,
                   "file truncated: it ends at byte " + std::to_string(all.size()) +
                       " inside the Header record; no messages",
                   pos);
    return;
  }
  parse(opcode, all.subspan(pos + kRecordHeader, length), Where{pos, {}}, [&](FieldReader& f) {
    info.profile = f.string("profile");
    info.library = f.string("library");
    return 0;
  });
  pos += kRecordHeader + length;

  if (complete && read_summary(footer_offset)) {
    return;
  }
  scan(pos, info, blocks);
}

Reader::Reader(const std::filesystem::path& path, ReaderOptions options)
    : impl_(std::make_unique<Impl>(path, options)) {
  impl_->open();
}

Reader::~Reader() = default;
Reader::Reader(Reader&&) noexcept = default;
Reader& Reader::operator=(Reader&&) noexcept = default;

const FileInfo& Reader::info() const { return impl_->info; }

const std::filesystem::path& Reader::path() const { return impl_->path; }

void Reader::verify() const {
  const Impl& r = *impl_;
  if (!r.info.from_summary) {
    return;  // scanned, hence checked, on opening
  }
  FileInfo scanned;
  std::vector<Block> scanned_blocks;
  const auto all = r.bytes();
  const auto header_length = detail::load_le<std::uint64_t>(all.data() + kMagic.size() + 1);
  r.scan(kMagic.size() + kRecordHeader + header_length, scanned, scanned_blocks);
  const Statistics& said = r.info.statistics;
  const Statistics& found = scanned.statistics;
  if (said.message_count != found.message_count ||
      said.channel_message_counts != found.channel_message_counts) {
    throw r.error(0, "the Statistics record says " + std::to_string(said.message_count) +
                         " messages, the data section holds " +
                         std::to_string(found.message_count) +
                         " (or the per-channel counts differ)");
  }
  if (scanned.chunks.size() != r.info.chunks.size()) {
    throw r.error(0, "the summary indexes " + std::to_string(r.info.chunks.size()) +
                         " chunks, the data section holds " +
                         std::to_string(scanned.chunks.size()));
  }
  for (std::size_t i = 0; i < scanned.chunks.size(); ++i) {
    if (scanned.chunks[i].offset != r.info.chunks[i].offset ||
        scanned.chunks[i].length != r.info.chunks[i].length) {
      throw r.error(scanned.chunks[i].offset, "the chunk here differs from its ChunkIndex record");
    }
  }
}

// ---------------------------------------------------------------------------
// Message iteration

struct MessageCursor::State {
  // A loaded block: its records (in the file or in buffer) and, in log-time
  // order, how many of its messages are still in the heap.
  struct Slot {
    std::uint64_t offset = 0;
    bool chunk = false;
    std::span<const std::uint8_t> records;
    ByteBuffer buffer;
    std::size_t pending = 0;
  };
  // A message waiting in the log-time heap; ordered by (log_time, offset, at).
  struct Entry {
    std::uint64_t log_time;
    std::uint64_t offset;  // of its block
    std::uint64_t at;      // in the block's records
    std::uint32_t slot;
  };
  static bool later(const Entry& a, const Entry& b) {
    return std::tie(a.log_time, a.offset, a.at) > std::tie(b.log_time, b.offset, b.at);
  }

  const Reader::Impl* reader = nullptr;
  Order order = Order::log_time;
  std::vector<Block> blocks;
  std::size_t next_block = 0;
  std::vector<Slot> slots;
  std::vector<std::uint32_t> free_slots;
  std::vector<Entry> heap;
  std::optional<std::uint32_t> returned_slot;  // holds the data of the last returned message
  std::uint64_t file_at = 0;                   // file order: next record in slots[0]
  MessageView view;
  detail::Decompressor decompressor;

  // Loads blocks[next_block++] into a free slot; returns the slot.
  std::uint32_t load_next() {
    const Block& block = blocks[next_block++];
    std::uint32_t index = 0;
    if (free_slots.empty()) {
      index = static_cast<std::uint32_t>(slots.size());
      slots.emplace_back();
    } else {
      index = free_slots.back();
      free_slots.pop_back();
    }
    Slot& slot = slots[index];
    slot.offset = block.offset;
    slot.chunk = block.chunk;
    slot.pending = 0;
    if (block.chunk) {
      const ChunkHeader chunk = reader->chunk_at(block.offset);
      slot.records = reader->chunk_records(block.offset, chunk, slot.buffer, decompressor);
    } else {
      // A Message record outside chunks: its record is the block's only record.
      const auto length = detail::load_le<std::uint64_t>(reader->bytes().data() + block.offset + 1);
      slot.records = reader->bytes().subspan(block.offset, kRecordHeader + length);
    }
    return index;
  }

  // Fills view from the Message record content at byte `at` of a slot's records.
  void make_view(const Slot& slot, std::span<const std::uint8_t> content, std::uint64_t at) {
    const Where where = slot.chunk ? Where{slot.offset, at} : Where{slot.offset, {}};
    const auto m = reader->parse(as_byte(Opcode::message), content, where, message_fields);
    const auto channel = reader->info.channels.find(m.channel_id);
    if (channel == reader->info.channels.end()) {
      throw reader->error(slot.offset, "Message record" + where_text(where) +
                                           ": unknown channel id " + std::to_string(m.channel_id));
    }
    view.channel = &channel->second;
    view.schema = nullptr;
    if (channel->second.schema_id != 0) {
      const auto schema = reader->info.schemas.find(channel->second.schema_id);
      view.schema = schema == reader->info.schemas.end() ? nullptr : &schema->second;
    }
    view.sequence = m.sequence;
    view.log_time = m.log_time;
    view.publish_time = m.publish_time;
    view.data = m.data;
  }

  void release(std::uint32_t index) {
    if (--slots[index].pending == 0) {
      free_slots.push_back(index);
    }
  }

  const MessageView* next_in_file_order();
  const MessageView* next_in_log_time_order();
};

const MessageView* MessageCursor::State::next_in_file_order() {
  // slots[0] is the current block; file_at the next record in it.
  for (;;) {
    if (!slots.empty()) {
      Slot& slot = slots[0];
      while (file_at < slot.records.size()) {
        const std::uint64_t at = file_at;
        const std::uint64_t left = slot.records.size() - at;
        if (left < kRecordHeader) {
          throw reader->error(slot.offset, "Chunk record: stray bytes at the end of its records");
        }
        const std::uint8_t opcode = slot.records[at];
        const auto length = detail::load_le<std::uint64_t>(slot.records.data() + at + 1);
        if (length > left - kRecordHeader) {
          throw reader->error(slot.offset, "Chunk record: the " + opcode_name(opcode) +
                                               " record at byte " + std::to_string(at) +
                                               " of its records runs past their end");
        }
        file_at += kRecordHeader + length;
        if (opcode == as_byte(Opcode::message)) {
          make_view(slot, slot.records.subspan(at + kRecordHeader, length), at);
          return &view;
        }
      }
    }
    if (next_block == blocks.size()) {
      return nullptr;
    }
    free_slots.clear();
    if (!slots.empty()) {
      free_slots.push_back(0);
    }
    load_next();
    file_at = 0;
  }
}

const MessageView* MessageCursor::State::next_in_log_time_order() {
  if (returned_slot) {
    release(*returned_slot);
    returned_slot.reset();
  }
  // Load every block that may hold a message before the heap's earliest.
  while (next_block < blocks.size() &&
         (heap.empty() || blocks[next_block].start_time <= heap.front().log_time)) {
    const std::uint32_t index = load_next();
    Slot& slot = slots[index];
    reader->for_each_chunk_record(
        slot.offset, slot.records,
        [&](std::uint8_t opcode, std::span<const std::uint8_t> content, std::uint64_t at) {
          if (opcode != as_byte(Opcode::message)) {
            return;
          }
          if (content.size() < kMessageFields) {
            make_view(slot, content, at);  // throws the field error
          }
          const auto log_time = detail::load_le<std::uint64_t>(content.data() + 6);
          heap.push_back({log_time, slot.offset, at, index});
          std::push_heap(heap.begin(), heap.end(), later);
          ++slot.pending;
        });
    if (slot.pending == 0) {
      free_slots.push_back(index);
    }
  }
  if (heap.empty()) {
    return nullptr;
  }
  std::pop_heap(heap.begin(), heap.end(), later);
  const Entry entry = heap.back();
  heap.pop_back();
  const Slot& slot = slots[entry.slot];
  const auto length = detail::load_le<std::uint64_t>(slot.records.data() + entry.at + 1);
  make_view(slot, slot.records.subspan(entry.at + kRecordHeader, length), entry.at);
  returned_slot = entry.slot;
  return &view;
}

MessageCursor::MessageCursor(std::unique_ptr<State> state) : state_(std::move(state)) {}
MessageCursor::~MessageCursor() = default;
MessageCursor::MessageCursor(MessageCursor&&) noexcept = default;
MessageCursor& MessageCursor::operator=(MessageCursor&&) noexcept = default;

const MessageView* MessageCursor::next() {
  return state_->order == Order::file ? state_->next_in_file_order()
                                      : state_->next_in_log_time_order();
}

MessageCursor Reader::messages(Order order) const {
  auto state = std::make_unique<MessageCursor::State>();
  state->reader = impl_.get();
  state->order = order;
  state->blocks = impl_->blocks;
  if (order == Order::log_time) {
    std::stable_sort(state->blocks.begin(), state->blocks.end(),
                     [](const Block& a, const Block& b) { return a.start_time < b.start_time; });
  }
  return MessageCursor(std::move(state));
}

}  // namespace wbi::mcap
