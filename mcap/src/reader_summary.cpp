// The MCAP reader's use of the summary section: the Footer, Statistics and
// ChunkIndex records that stand in for a scan of the data section.
#include "reader_impl.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "crc32.hpp"

namespace wbi::mcap {

using namespace detail;

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

}  // namespace wbi::mcap
