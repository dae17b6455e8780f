// The MCAP reader's record-level decoding: the fields of single records, the
// schema and channel tables, and loading a chunk's records (decompression, CRC).
#include "reader_impl.hpp"

#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "crc32.hpp"

namespace wbi::mcap {

using namespace detail;

namespace detail {

std::string hex32(std::uint32_t value) {
  std::array<char, 16> text{};
  std::snprintf(text.data(), text.size(), "0x%08x", value);
  return text.data();
}

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

}  // namespace detail

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

}  // namespace wbi::mcap
