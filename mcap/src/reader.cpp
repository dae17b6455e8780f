// wbi::mcap::Reader: opening a file (magic, Header, then the summary or a scan)
// and its public API; the parts are in reader_*.cpp and message_cursor.cpp.
#include "wbi/mcap/reader.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "reader_impl.hpp"

namespace wbi::mcap {

using namespace detail;

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

}  // namespace wbi::mcap
