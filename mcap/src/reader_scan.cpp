// The MCAP reader's scan of the data section, record by record: the file's
// index when it has no usable summary, and where a truncated file was cut.
#include "reader_impl.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "crc32.hpp"

namespace wbi::mcap {

using namespace detail;

namespace detail {

void mark_truncated(FileInfo& info, std::span<const std::uint8_t> all, std::string description,
                    std::uint64_t readable_bytes, std::uint8_t opcode, std::uint64_t record_offset,
                    std::uint64_t record_length) {
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

}  // namespace detail

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

}  // namespace wbi::mcap
