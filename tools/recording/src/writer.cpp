#include "wbi/mcap/writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "byte_buffer.hpp"
#include "codec.hpp"
#include "crc32.hpp"

namespace wbi::mcap {

namespace {

using detail::ByteBuffer;

// Fixed sizes of record contents (spec field lists).
constexpr std::size_t kRecordHeader = 1 + 8;           // opcode, length
constexpr std::size_t kMessageFields = 2 + 4 + 8 + 8;  // channel, sequence, log and publish time
constexpr std::size_t kMessageIndexEntry = 8 + 8;      // log_time, offset
constexpr std::uint64_t kFooterContent = 8 + 8 + 4;    // summary start, offset start, CRC

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
void encode_schema(ByteBuffer& out, const Schema& schema) {
  out.clear();
  const auto at = out.begin_record(Opcode::schema);
  out.put(schema.id);
  out.put_string(schema.name);
  out.put_string(schema.encoding);
  out.put_bytes32(schema.data);
  out.end_record(at);
}

// Channel: id, schema id, topic, message encoding, metadata. Likewise.
void encode_channel(ByteBuffer& out, const Channel& channel) {
  out.clear();
  const auto at = out.begin_record(Opcode::channel);
  out.put(channel.id);
  out.put(channel.schema_id);
  out.put_string(channel.topic);
  out.put_string(channel.message_encoding);
  out.put_key_values(channel.metadata);
  out.end_record(at);
}

}  // namespace

struct Writer::Impl {
  std::filesystem::path path;
  WriterOptions options;
  std::FILE* file = nullptr;
  bool failed = false;  // a write failed: close() only releases the file
  Section section = Section::data;
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
  ByteBuffer chunk_records;
  std::vector<std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_message_index;
  std::vector<std::uint16_t> chunk_channels;  // ids with entries in the open chunk
  std::uint64_t chunk_start_time = 0;
  std::uint64_t chunk_end_time = 0;

  detail::Compressor compressor;
  ByteBuffer compressed;  // reused compression output
  ByteBuffer scratch;     // reused record encoding
  std::vector<ChunkIndexEntry> chunk_indexes;
  std::vector<MetadataIndexEntry> metadata_indexes;

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
    if (section == Section::data) {
      data_crc = detail::crc32(data_crc, bytes);
    } else if (section == Section::summary) {
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

void Writer::Impl::write_chunk() {
  if (chunk_records.empty()) {
    return;
  }
  const auto records = chunk_records.span();
  const std::uint32_t uncompressed_crc = detail::crc32(0, records);
  std::span<const std::uint8_t> payload = records;
  if (options.compression != Compression::none) {
    compressor.compress(records, compressed);
    payload = compressed.span();
  }
  const std::string_view compression = compression_field(options.compression);

  ChunkIndexEntry entry;
  entry.chunk.offset = offset;
  entry.chunk.message_start_time = chunk_start_time;
  entry.chunk.message_end_time = chunk_end_time;
  entry.chunk.compression = compression;
  entry.chunk.compressed_size = payload.size();
  entry.chunk.uncompressed_size = records.size();

  // Chunk: start, end, uncompressed size, uncompressed CRC, compression, records.
  scratch.clear();
  scratch.put(static_cast<std::uint8_t>(Opcode::chunk));
  scratch.put(
      static_cast<std::uint64_t>(8 + 8 + 8 + 4 + 4 + compression.size() + 8 + payload.size()));
  scratch.put(chunk_start_time);
  scratch.put(chunk_end_time);
  scratch.put(static_cast<std::uint64_t>(records.size()));
  scratch.put(uncompressed_crc);
  scratch.put_string(compression);
  scratch.put(static_cast<std::uint64_t>(payload.size()));
  write_scratch();
  write_bytes(payload);
  entry.chunk.length = offset - entry.chunk.offset;

  // MessageIndex per channel: channel id, then (log_time, offset) pairs sorted by log time.
  std::sort(chunk_channels.begin(), chunk_channels.end());
  const std::uint64_t indexes_start = offset;
  for (const std::uint16_t id : chunk_channels) {
    auto& index = chunk_message_index[id];
    if (!std::is_sorted(index.begin(), index.end())) {
      std::sort(index.begin(), index.end());
    }
    entry.message_index_offsets[id] = offset;
    const std::size_t entries_bytes = index.size() * kMessageIndexEntry;
    scratch.clear();
    scratch.put(static_cast<std::uint8_t>(Opcode::message_index));
    scratch.put(static_cast<std::uint64_t>(2 + 4 + entries_bytes));
    scratch.put(id);
    scratch.put(static_cast<std::uint32_t>(entries_bytes));
    for (const auto& [log_time, record_offset] : index) {
      scratch.put(log_time);
      scratch.put(record_offset);
    }
    write_scratch();
    index.clear();
  }
  entry.message_index_length = offset - indexes_start;
  chunk_indexes.push_back(std::move(entry));

  chunk_channels.clear();
  chunk_records.clear();
  ++written.chunks;
}

void Writer::Impl::write_summary_and_footer() {
  // DataEnd: the CRC of everything before it.
  section = Section::data_end;
  scratch.clear();
  scratch.put(static_cast<std::uint8_t>(Opcode::data_end));
  scratch.put(std::uint64_t{4});
  scratch.put(data_crc);
  write_scratch();

  section = Section::summary;
  const std::uint64_t summary_start = offset;
  struct Group {
    Opcode opcode;
    std::uint64_t start;
    std::uint64_t length;
  };
  std::vector<Group> groups;
  const auto write_group = [&](Opcode opcode, const auto& encode_records) {
    const std::uint64_t start = offset;
    encode_records();
    if (offset > start) {
      groups.push_back({opcode, start, offset - start});
    }
  };

  write_group(Opcode::schema, [&] {
    for (const auto& schema : schemas) {
      encode_schema(scratch, schema);
      write_scratch();
    }
  });
  write_group(Opcode::channel, [&] {
    for (const auto& channel : channels) {
      encode_channel(scratch, channel);
      write_scratch();
    }
  });
  write_group(Opcode::statistics, [&] {
    scratch.clear();
    const auto at = scratch.begin_record(Opcode::statistics);
    scratch.put(written.messages);
    scratch.put(static_cast<std::uint16_t>(schemas.size()));
    scratch.put(static_cast<std::uint32_t>(channels.size()));
    scratch.put(std::uint32_t{0});  // attachments
    scratch.put(static_cast<std::uint32_t>(metadata_indexes.size()));
    scratch.put(static_cast<std::uint32_t>(chunk_indexes.size()));
    scratch.put(message_start_time);
    scratch.put(message_end_time);
    std::uint32_t counts_bytes = 0;
    for (const std::uint64_t count : channel_message_counts) {
      counts_bytes += count > 0 ? 2 + 8 : 0;
    }
    scratch.put(counts_bytes);
    for (std::size_t id = 1; id < channel_message_counts.size(); ++id) {
      if (channel_message_counts[id] > 0) {
        scratch.put(static_cast<std::uint16_t>(id));
        scratch.put(channel_message_counts[id]);
      }
    }
    scratch.end_record(at);
    write_scratch();
  });
  write_group(Opcode::chunk_index, [&] {
    for (const auto& entry : chunk_indexes) {
      scratch.clear();
      const auto at = scratch.begin_record(Opcode::chunk_index);
      scratch.put(entry.chunk.message_start_time);
      scratch.put(entry.chunk.message_end_time);
      scratch.put(entry.chunk.offset);
      scratch.put(entry.chunk.length);
      scratch.put(static_cast<std::uint32_t>(entry.message_index_offsets.size() * (2 + 8)));
      for (const auto& [id, index_offset] : entry.message_index_offsets) {
        scratch.put(id);
        scratch.put(index_offset);
      }
      scratch.put(entry.message_index_length);
      scratch.put_string(entry.chunk.compression);
      scratch.put(entry.chunk.compressed_size);
      scratch.put(entry.chunk.uncompressed_size);
      scratch.end_record(at);
      write_scratch();
    }
  });
  write_group(Opcode::metadata_index, [&] {
    for (const auto& entry : metadata_indexes) {
      scratch.clear();
      const auto at = scratch.begin_record(Opcode::metadata_index);
      scratch.put(entry.offset);
      scratch.put(entry.length);
      scratch.put_string(entry.name);
      scratch.end_record(at);
      write_scratch();
    }
  });

  // Summary offsets: where each group starts and how long it is.
  const std::uint64_t summary_offset_start = offset;
  for (const auto& group : groups) {
    scratch.clear();
    const auto at = scratch.begin_record(Opcode::summary_offset);
    scratch.put(static_cast<std::uint8_t>(group.opcode));
    scratch.put(group.start);
    scratch.put(group.length);
    scratch.end_record(at);
    write_scratch();
  }

  // Footer; its CRC covers the summary start up to and including summary_offset_start.
  scratch.clear();
  scratch.put(static_cast<std::uint8_t>(Opcode::footer));
  scratch.put(kFooterContent);
  scratch.put(summary_start);
  scratch.put(summary_offset_start);
  write_scratch();
  section = Section::data_end;  // the CRC field and the magic count towards nothing
  scratch.clear();
  scratch.put(summary_crc);
  scratch.append(kMagic.data(), kMagic.size());
  write_scratch();
}

Writer::Writer(const std::filesystem::path& path, WriterOptions options)
    : impl_(std::make_unique<Impl>(path, std::move(options))) {
  Impl& w = *impl_;
  if (w.options.chunk_size == 0) {
    throw std::invalid_argument("mcap::Writer: chunk_size must be > 0");
  }
  w.file = std::fopen(path.c_str(), "wb");
  if (w.file == nullptr) {
    throw std::runtime_error(path.string() + ": cannot create: " + std::strerror(errno));
  }
  w.chunk_records.reserve(w.options.chunk_size + 1024);
  w.channel_message_counts.resize(1);
  w.chunk_message_index.resize(1);

  // Magic, then Header{profile, library}.
  w.scratch.append(kMagic.data(), kMagic.size());
  const auto at = w.scratch.begin_record(Opcode::header);
  w.scratch.put_string(w.options.profile);
  w.scratch.put_string(w.options.library);
  w.scratch.end_record(at);
  try {
    w.write_scratch();
    flush();
  } catch (...) {
    std::fclose(w.file);
    throw;
  }
}

Writer::Writer(Writer&&) noexcept = default;

Writer::~Writer() {
  if (!impl_) {
    return;  // moved from
  }
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw; close() reports
  }
  if (impl_->file != nullptr) {
    std::fclose(impl_->file);
  }
}

std::uint16_t Writer::add_schema(std::string_view name, std::string_view encoding,
                                 std::span<const std::uint8_t> data) {
  Impl& w = *impl_;
  w.check_open("add_schema");
  for (const auto& schema : w.schemas) {
    if (schema.name == name && schema.encoding == encoding &&
        std::equal(schema.data.begin(), schema.data.end(), data.begin(), data.end())) {
      return schema.id;
    }
  }
  if (w.schemas.size() >= 0xFFFF) {
    throw std::length_error(w.path.string() + ": more than 65535 schemas");
  }
  Schema schema{static_cast<std::uint16_t>(w.schemas.size() + 1),
                std::string(name),
                std::string(encoding),
                {data.begin(), data.end()}};
  encode_schema(w.scratch, schema);
  w.write_scratch();
  w.schemas.push_back(std::move(schema));
  return w.schemas.back().id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, std::string_view topic,
                                  std::string_view message_encoding, const KeyValues& metadata) {
  Impl& w = *impl_;
  w.check_open("add_channel");
  if (schema_id > w.schemas.size()) {
    throw std::invalid_argument("mcap::Writer::add_channel: unknown schema id " +
                                std::to_string(schema_id) + " for topic '" + std::string(topic) +
                                "'");
  }
  if (w.channels.size() >= 0xFFFF) {
    throw std::length_error(w.path.string() + ": more than 65535 channels");
  }
  Channel channel{static_cast<std::uint16_t>(w.channels.size() + 1), schema_id, std::string(topic),
                  std::string(message_encoding), metadata};
  encode_channel(w.scratch, channel);
  w.write_scratch();
  w.channels.push_back(std::move(channel));
  w.channel_message_counts.push_back(0);
  w.chunk_message_index.emplace_back().reserve(256);
  return w.channels.back().id;
}

void Writer::write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                   std::uint64_t publish_time, std::span<const std::uint8_t> data) {
  Impl& w = *impl_;
  if (w.file == nullptr || w.failed) {
    w.check_open("write");
  }
  if (channel_id == 0 || channel_id > w.channels.size()) {
    throw std::invalid_argument("mcap::Writer::write: unknown channel id " +
                                std::to_string(channel_id));
  }
  // Message: channel id, sequence, log time, publish time, data (the rest).
  const std::uint64_t record_offset = w.chunk_records.size();
  const std::size_t record_size = kRecordHeader + kMessageFields + data.size();
  std::uint8_t* out = w.chunk_records.tail(record_size);
  out[0] = static_cast<std::uint8_t>(Opcode::message);
  detail::store_le(out + 1, static_cast<std::uint64_t>(kMessageFields + data.size()));
  detail::store_le(out + 9, channel_id);
  detail::store_le(out + 11, sequence);
  detail::store_le(out + 15, log_time);
  detail::store_le(out + 23, publish_time);
  if (!data.empty()) {
    std::memcpy(out + kRecordHeader + kMessageFields, data.data(), data.size());
  }
  w.chunk_records.grow(record_size);

  auto& index = w.chunk_message_index[channel_id];
  if (index.empty()) {
    w.chunk_channels.push_back(channel_id);
  }
  index.emplace_back(log_time, record_offset);
  if (record_offset == 0) {
    w.chunk_start_time = log_time;
    w.chunk_end_time = log_time;
  } else {
    w.chunk_start_time = std::min(w.chunk_start_time, log_time);
    w.chunk_end_time = std::max(w.chunk_end_time, log_time);
  }
  if (w.written.messages == 0) {
    w.message_start_time = log_time;
    w.message_end_time = log_time;
  } else {
    w.message_start_time = std::min(w.message_start_time, log_time);
    w.message_end_time = std::max(w.message_end_time, log_time);
  }
  ++w.channel_message_counts[channel_id];
  ++w.written.messages;
  w.written.payload_bytes += data.size();

  if (w.chunk_records.size() >= w.options.chunk_size) {
    w.write_chunk();
  }
}

void Writer::write_metadata(std::string_view name, const KeyValues& metadata) {
  Impl& w = *impl_;
  w.check_open("write_metadata");
  // Metadata: name, key/values.
  w.scratch.clear();
  const auto at = w.scratch.begin_record(Opcode::metadata);
  w.scratch.put_string(name);
  w.scratch.put_key_values(metadata);
  w.scratch.end_record(at);
  const std::uint64_t record_offset = w.offset;
  w.write_scratch();
  w.metadata_indexes.push_back({record_offset, w.offset - record_offset, std::string(name)});
}

void Writer::flush() {
  Impl& w = *impl_;
  w.check_open("flush");
  w.write_chunk();
  if (std::fflush(w.file) != 0) {
    w.fail(std::string("flush failed: ") + std::strerror(errno));
  }
}

void Writer::close() {
  Impl& w = *impl_;
  if (w.file == nullptr) {
    return;
  }
  if (!w.failed) {
    try {
      w.write_chunk();
      w.write_summary_and_footer();
    } catch (...) {
      std::fclose(w.file);
      w.file = nullptr;
      throw;
    }
  }
  const bool failed = w.failed;
  const int closed = std::fclose(w.file);
  w.file = nullptr;
  if (closed != 0 && !failed) {
    w.fail(std::string("close failed: ") + std::strerror(errno));
  }
}

const WriterStatistics& Writer::statistics() const { return impl_->written; }

const std::filesystem::path& Writer::path() const { return impl_->path; }

}  // namespace wbi::mcap
