// The MCAP writer's index and closing records: each chunk with its MessageIndex
// records, then DataEnd, the summary section (with its offsets) and the Footer.
#include <algorithm>
#include <string_view>
#include <utility>
#include <vector>

#include "writer_impl.hpp"

namespace wbi::mcap {

namespace {

using detail::ByteBuffer;

constexpr std::size_t kMessageIndexEntry = 8 + 8;    // log_time, offset
constexpr std::uint64_t kFooterContent = 8 + 8 + 4;  // summary start, offset start, CRC

}  // namespace

namespace detail {

void encode_schema(ByteBuffer& out, const Schema& schema) {
  out.clear();
  const auto at = out.begin_record(Opcode::schema);
  out.put(schema.id);
  out.put_string(schema.name);
  out.put_string(schema.encoding);
  out.put_bytes32(schema.data);
  out.end_record(at);
}

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

}  // namespace detail

using detail::ChunkIndexEntry;
using detail::encode_channel;
using detail::encode_schema;
using detail::Section;

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

}  // namespace wbi::mcap
