// wbi::mcap::Writer's public API: creating the file (magic, Header), adding
// schemas and channels, writing messages and metadata, flushing and closing.
#include "wbi/mcap/writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "writer_impl.hpp"

namespace wbi::mcap {

namespace {

constexpr std::size_t kRecordHeader = 1 + 8;           // opcode, length
constexpr std::size_t kMessageFields = 2 + 4 + 8 + 8;  // channel, sequence, log and publish time

}  // namespace

using detail::encode_channel;
using detail::encode_schema;

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
