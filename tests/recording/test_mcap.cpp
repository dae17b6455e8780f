// wbi::mcap: write/read round trips with each compression, summary against
// scan, flushed files read while being written, truncation at every cut point,
// corrupt files, hand-written files in layouts our writer does not produce, and
// the writer's allocation behaviour.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "mcap_samples.hpp"

namespace {

using wbi::mcap::Compression;
using wbi::mcap::FormatError;
using wbi::mcap::Order;
using wbi::mcap::Reader;
using wbi::mcap::Writer;
using wbi::mcap::WriterOptions;
using wbi::test::by_log_time;
using wbi::test::read_all;
using wbi::test::read_bytes;
using wbi::test::SampleMessage;
using wbi::test::TempDir;
using wbi::test::write_bytes;
using wbi::test::write_sample;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Compares message lists, reporting the first difference only.
void expect_same(const std::vector<SampleMessage>& got, const std::vector<SampleMessage>& want,
                 const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].topic, want[i].topic) << what << ", message " << i;
    ASSERT_EQ(got[i].type, want[i].type) << what << ", message " << i;
    ASSERT_EQ(got[i].sequence, want[i].sequence) << what << ", message " << i;
    ASSERT_EQ(got[i].log_time, want[i].log_time) << what << ", message " << i;
    ASSERT_EQ(got[i].publish_time, want[i].publish_time) << what << ", message " << i;
    ASSERT_EQ(got[i].data, want[i].data) << what << ", message " << i;
  }
}

WriterOptions options_with(Compression compression, std::size_t chunk_size) {
  WriterOptions options;
  options.compression = compression;
  options.chunk_size = chunk_size;
  return options;
}

std::uint64_t load_u64(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    value |= static_cast<std::uint64_t>(bytes[at + i]) << (8 * i);
  }
  return value;
}

void store_u64(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint64_t value) {
  for (std::size_t i = 0; i < 8; ++i) {
    bytes[at + i] = static_cast<std::uint8_t>(value >> (8 * i));
  }
}

constexpr std::size_t kFooterAt = 8 + 29;  // the Footer record starts this far before the end

std::uint64_t summary_start(const std::vector<std::uint8_t>& bytes) {
  return load_u64(bytes, bytes.size() - kFooterAt + 9);
}

// ---------------------------------------------------------------------------
// Round trips

class McapCompression : public ::testing::TestWithParam<Compression> {};

TEST_P(McapCompression, RoundTripInFileAndLogTimeOrder) {
  TempDir dir;
  const auto file = dir / "run.mcap";
  const auto written = write_sample(file, options_with(GetParam(), 32 * 1024), 5000);

  const Reader reader(file);
  const auto& info = reader.info();
  EXPECT_TRUE(info.from_summary);
  EXPECT_FALSE(info.truncated);
  EXPECT_TRUE(info.warnings.empty());
  EXPECT_EQ(info.profile, "wbi");
  EXPECT_EQ(info.statistics.message_count, 5000u);
  EXPECT_EQ(info.statistics.schema_count, 3u);
  EXPECT_EQ(info.statistics.channel_count, 5u);
  EXPECT_EQ(info.statistics.chunk_count, info.chunks.size());
  EXPECT_GT(info.chunks.size(), 10u);
  for (const auto& chunk : info.chunks) {
    EXPECT_EQ(chunk.compression, wbi::mcap::compression_field(GetParam()));
  }
  for (const auto& [id, count] : info.statistics.channel_message_counts) {
    EXPECT_EQ(count, 1000u) << "channel " << id;
  }
  const auto sorted = by_log_time(written);
  EXPECT_EQ(info.statistics.message_start_time, sorted.front().log_time);
  EXPECT_EQ(info.statistics.message_end_time, sorted.back().log_time);

  // Schemas and channels as written.
  ASSERT_EQ(info.channels.size(), 5u);
  const auto& sensors = info.channels.at(1);
  EXPECT_EQ(sensors.topic, "wbi/arm/sensors");
  EXPECT_EQ(sensors.message_encoding, "cdr");
  EXPECT_EQ(sensors.metadata.at("reliability"), "best_effort");
  const auto& schema = info.schemas.at(sensors.schema_id);
  EXPECT_EQ(schema.encoding, "omgidl");
  EXPECT_EQ(std::string(schema.data.begin(), schema.data.end()), wbi::test::kJointStateIdl);
  EXPECT_EQ(info.channels.at(3).schema_id, sensors.schema_id);
  EXPECT_EQ(info.channels.at(4).schema_id, 0);

  expect_same(read_all(reader, Order::file), written, "file order");
  expect_same(read_all(reader, Order::log_time), sorted, "log-time order");
  EXPECT_NO_THROW(reader.verify());
}

INSTANTIATE_TEST_SUITE_P(All, McapCompression,
                         ::testing::Values(Compression::none, Compression::lz4, Compression::zstd),
                         [](const auto& param) {
                           return std::string(wbi::mcap::compression_name(param.param));
                         });

TEST(Mcap, SummaryAndScanAgree) {
  TempDir dir;
  const auto file = dir / "run.mcap";
  const auto written = write_sample(file, options_with(Compression::zstd, 16 * 1024), 3000);
  // The same data section without summary and footer: the reader must scan it.
  const auto bytes = read_bytes(file);
  write_bytes(dir / "scan.mcap", bytes, summary_start(bytes));

  const Reader indexed(file);
  const Reader scanned(dir / "scan.mcap");
  ASSERT_TRUE(indexed.info().from_summary);
  ASSERT_FALSE(scanned.info().from_summary);
  EXPECT_TRUE(scanned.info().truncated);
  const auto& a = indexed.info().statistics;
  const auto& b = scanned.info().statistics;
  EXPECT_EQ(a.message_count, b.message_count);
  EXPECT_EQ(a.schema_count, b.schema_count);
  EXPECT_EQ(a.channel_count, b.channel_count);
  EXPECT_EQ(a.chunk_count, b.chunk_count);
  EXPECT_EQ(a.message_start_time, b.message_start_time);
  EXPECT_EQ(a.message_end_time, b.message_end_time);
  EXPECT_EQ(a.channel_message_counts, b.channel_message_counts);
  ASSERT_EQ(indexed.info().channels.size(), scanned.info().channels.size());
  for (const auto& [id, channel] : indexed.info().channels) {
    const auto& other = scanned.info().channels.at(id);
    EXPECT_EQ(channel.topic, other.topic);
    EXPECT_EQ(channel.schema_id, other.schema_id);
    EXPECT_EQ(channel.message_encoding, other.message_encoding);
    EXPECT_EQ(channel.metadata, other.metadata);
  }
  ASSERT_EQ(indexed.info().schemas.size(), scanned.info().schemas.size());
  for (const auto& [id, schema] : indexed.info().schemas) {
    EXPECT_EQ(schema.name, scanned.info().schemas.at(id).name);
    EXPECT_EQ(schema.data, scanned.info().schemas.at(id).data);
  }
  ASSERT_EQ(indexed.info().chunks.size(), scanned.info().chunks.size());
  for (std::size_t i = 0; i < indexed.info().chunks.size(); ++i) {
    const auto& x = indexed.info().chunks[i];
    const auto& y = scanned.info().chunks[i];
    EXPECT_EQ(x.offset, y.offset);
    EXPECT_EQ(x.length, y.length);
    EXPECT_EQ(x.message_start_time, y.message_start_time);
    EXPECT_EQ(x.message_end_time, y.message_end_time);
    EXPECT_EQ(x.compression, y.compression);
    EXPECT_EQ(x.compressed_size, y.compressed_size);
    EXPECT_EQ(x.uncompressed_size, y.uncompressed_size);
  }
  expect_same(read_all(scanned, Order::file), written, "scan, file order");
  expect_same(read_all(scanned, Order::log_time), by_log_time(written), "scan, log-time order");
}

TEST(Mcap, FlushedDataIsReadableWhileWriting) {
  TempDir dir;
  const auto file = dir / "live.mcap";
  Writer writer(file, options_with(Compression::zstd, 1024 * 1024));
  const auto channel = writer.add_channel(writer.add_schema("T", "struct T { double x; };"), "t");
  const std::vector<std::uint8_t> payload(800, 7);
  for (std::uint32_t i = 0; i < 300; ++i) {
    writer.write(channel, i, 1000 + i, 1000 + i, payload);
  }
  writer.flush();
  for (std::uint32_t i = 300; i < 500; ++i) {  // still in the open chunk
    writer.write(channel, i, 1000 + i, 1000 + i, payload);
  }
  // What a reader sees of a recorder killed now.
  std::filesystem::copy_file(file, dir / "killed.mcap");
  {
    const Reader killed(dir / "killed.mcap");
    EXPECT_TRUE(killed.info().truncated);
    EXPECT_FALSE(killed.info().from_summary);
    ASSERT_FALSE(killed.info().warnings.empty());
    EXPECT_TRUE(contains(killed.info().warnings[0], "truncated")) << killed.info().warnings[0];
    EXPECT_EQ(killed.info().statistics.message_count, 300u);
    EXPECT_EQ(read_all(killed, Order::log_time).size(), 300u);
  }
  writer.close();
  const Reader closed(file);
  EXPECT_EQ(closed.info().statistics.message_count, 500u);
  EXPECT_TRUE(closed.info().warnings.empty());
}

// ---------------------------------------------------------------------------
// Truncation

// Reads the file cut to `cut` bytes: no exception, a prefix of the messages in
// file order, the same messages in log-time order, a truncation warning.
// Returns how many messages were read.
std::size_t check_cut(const TempDir& dir, const std::vector<std::uint8_t>& bytes, std::size_t cut,
                      const std::vector<SampleMessage>& written) {
  const auto file = dir / "cut.mcap";
  write_bytes(file, bytes, cut);
  std::optional<Reader> reader;
  try {
    reader.emplace(file);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "cut at " << cut << " of " << bytes.size() << ": " << e.what();
    return 0;
  }
  EXPECT_TRUE(reader->info().truncated) << "cut at " << cut;
  EXPECT_FALSE(reader->info().warnings.empty()) << "cut at " << cut;
  std::vector<SampleMessage> got;
  std::vector<SampleMessage> got_by_time;
  try {
    got = read_all(*reader, Order::file);
    got_by_time = read_all(*reader, Order::log_time);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "cut at " << cut << ": reading messages: " << e.what();
    return 0;
  }
  EXPECT_EQ(reader->info().statistics.message_count, got.size()) << "cut at " << cut;
  EXPECT_LE(got.size(), written.size()) << "cut at " << cut;
  for (std::size_t i = 0; i < std::min(got.size(), written.size()); ++i) {
    if (!(got[i] == written[i])) {
      ADD_FAILURE() << "cut at " << cut << ": message " << i << " is not the written one";
      break;
    }
  }
  EXPECT_EQ(got_by_time, by_log_time(got)) << "cut at " << cut;
  return got.size();
}

TEST(McapTruncation, EveryCutPointOfASmallFile) {
  const TempDir dir(wbi::test::fast_temp_base());
  const auto file = dir / "small.mcap";
  const auto written = write_sample(file, options_with(Compression::lz4, 300), 40, false, true);
  const auto bytes = read_bytes(file);
  ASSERT_LT(bytes.size(), 8'000u);
  ASSERT_GT(Reader(file).info().chunks.size(), 5u);
  std::size_t previous = 0;
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    const std::size_t count = check_cut(dir, bytes, cut, written);
    EXPECT_GE(count, previous) << "cut at " << cut << ": fewer messages than a shorter cut";
    previous = count;
    if (::testing::Test::HasFailure()) {
      return;  // one cut's failures are enough to read
    }
  }
  EXPECT_EQ(previous, written.size());  // a cut in the summary loses nothing
}

TEST(McapTruncation, SampledCutPointsOfALargerFile) {
  const TempDir dir(wbi::test::fast_temp_base());
  const auto file = dir / "large.mcap";
  const auto written = write_sample(file, options_with(Compression::zstd, 16 * 1024), 3000, true);
  const auto bytes = read_bytes(file);
  std::vector<std::size_t> cuts;
  for (std::size_t cut = 0; cut < bytes.size(); cut += bytes.size() / 150) {
    cuts.push_back(cut);
  }
  const auto chunks = Reader(file).info().chunks;
  for (std::size_t i = 0; i < chunks.size(); i += 10) {  // around the ends of every 10th chunk
    const auto& chunk = chunks[i];
    for (const std::size_t edge : {chunk.offset, chunk.offset + chunk.length}) {
      cuts.insert(cuts.end(), {edge - 1, edge, edge + 1, edge + 9});
    }
  }
  const std::size_t data_end = summary_start(bytes) - 13;
  cuts.insert(cuts.end(),
              {data_end, data_end + 1, data_end + 13, bytes.size() - 8, bytes.size() - 1});
  for (const std::size_t cut : cuts) {
    check_cut(dir, bytes, cut, written);
    if (::testing::Test::HasFailure()) {
      return;
    }
  }
  EXPECT_EQ(check_cut(dir, bytes, data_end + 13, written), written.size());
}

TEST(McapTruncation, EmptyAndTinyFiles) {
  TempDir dir;
  const std::vector<std::uint8_t> magic(wbi::mcap::kMagic.begin(), wbi::mcap::kMagic.end());
  for (const std::size_t size : {0, 3, 8, 12}) {
    auto bytes = magic;
    bytes.resize(std::max<std::size_t>(size, 8), 0x01);
    write_bytes(dir / "tiny.mcap", bytes, size);
    const Reader reader(dir / "tiny.mcap");
    EXPECT_TRUE(reader.info().truncated) << size;
    EXPECT_EQ(reader.info().statistics.message_count, 0u);
    EXPECT_EQ(reader.messages().next(), nullptr);
  }
}

// ---------------------------------------------------------------------------
// Corruption

struct Corrupt {
  std::string name;
  std::vector<std::uint8_t> bytes;
};

// Runs what() on the file and expects a FormatError at `offset` whose message
// names the file and contains `text`.
template <typename What>
void expect_format_error(const TempDir& dir, const Corrupt& corrupt, std::uint64_t offset,
                         const std::string& text, What&& what) {
  const auto file = dir / (corrupt.name + ".mcap");
  write_bytes(file, corrupt.bytes, corrupt.bytes.size());
  try {
    what(file);
    ADD_FAILURE() << corrupt.name << ": no error";
  } catch (const FormatError& e) {
    EXPECT_EQ(e.offset(), offset) << corrupt.name << ": " << e.what();
    EXPECT_TRUE(contains(e.what(), file.string() + ": byte " + std::to_string(offset) + ": "))
        << corrupt.name << ": " << e.what();
    EXPECT_TRUE(contains(e.what(), text)) << corrupt.name << ": " << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << corrupt.name << ": not a FormatError: " << e.what();
  }
}

const auto kOpen = [](const std::filesystem::path& file) { Reader reader(file); };
const auto kRead = [](const std::filesystem::path& file) {
  const Reader reader(file);
  read_all(reader, Order::log_time);
};
const auto kVerify = [](const std::filesystem::path& file) { Reader(file).verify(); };

TEST(McapCorruption, ErrorsNameTheFileAndTheOffset) {
  TempDir dir;
  const auto file = dir / "good.mcap";
  write_sample(file, options_with(Compression::none, 4096), 200);
  const auto good = read_bytes(file);
  const auto chunks = Reader(file).info().chunks;
  ASSERT_GT(chunks.size(), 3u);
  const std::uint64_t footer = good.size() - kFooterAt;
  const std::uint64_t summary = summary_start(good);
  const std::uint64_t data_end = summary - 13;
  const std::uint64_t first_record = 8 + 9 + load_u64(good, 9);  // after magic and Header

  Corrupt magic{"magic", good};
  magic.bytes[1] = 'X';
  expect_format_error(dir, magic, 0, "bad magic", kOpen);

  // A payload byte of chunk 1 (uncompressed): its CRC no longer matches.
  Corrupt payload{"payload", good};
  payload.bytes[chunks[1].offset + chunks[1].length - 20] ^= 0xFF;
  expect_format_error(dir, payload, chunks[1].offset, "CRC mismatch", kRead);
  Corrupt payload_scanned{"payload_scanned", payload.bytes};
  payload_scanned.bytes.resize(summary);  // no summary: found while scanning on open
  expect_format_error(dir, payload_scanned, chunks[1].offset, "CRC mismatch", kOpen);

  // A byte of the MessageIndex after chunk 0: only the data-section CRC sees it.
  Corrupt index{"index", good};
  index.bytes[chunks[0].offset + chunks[0].length + 9 + 2 + 4 + 1] ^= 0xFF;
  expect_format_error(dir, index, data_end, "data section CRC mismatch", kVerify);
  EXPECT_NO_THROW(kRead(dir / "index.mcap"));

  Corrupt summary_byte{"summary", good};
  summary_byte.bytes[summary + 20] ^= 0xFF;
  expect_format_error(dir, summary_byte, summary, "summary section CRC mismatch", kOpen);

  Corrupt footer_length{"footer_length", good};
  footer_length.bytes[footer + 1] = 21;
  expect_format_error(dir, footer_length, footer, "bad Footer record", kOpen);

  // Lengths beyond the file: the Header's, and a chunk's (seen through its index).
  Corrupt header_length{"header_length", good};
  store_u64(header_length.bytes, 9, std::uint64_t{1} << 40);
  expect_format_error(dir, header_length, 8, "runs past the end of the file", kOpen);
  Corrupt chunk_length{"chunk_length", good};
  store_u64(chunk_length.bytes, chunks[2].offset + 1, std::uint64_t{1} << 40);
  expect_format_error(dir, chunk_length, chunks[2].offset, "expected the Chunk record", kOpen);
  // The same in a complete file without summary (Footer summary_start 0): scanned.
  Corrupt unindexed{"unindexed", chunk_length.bytes};
  unindexed.bytes.resize(summary);
  unindexed.bytes.insert(unindexed.bytes.end(), {0x02, 20, 0, 0, 0, 0, 0, 0, 0});
  unindexed.bytes.resize(unindexed.bytes.size() + 20, 0);
  unindexed.bytes.insert(unindexed.bytes.end(), wbi::mcap::kMagic.begin(), wbi::mcap::kMagic.end());
  expect_format_error(dir, unindexed, chunks[2].offset, "runs past the end of the file", kOpen);

  Corrupt opcode{"opcode", good};
  opcode.bytes[first_record] = 0x00;
  opcode.bytes.resize(summary);
  expect_format_error(dir, opcode, first_record, "invalid opcode 0x00", kOpen);

  // Compressed chunks: a size that disagrees with the zstd frame, an unknown codec.
  const auto zstd_file = dir / "zstd.mcap";
  write_sample(zstd_file, options_with(Compression::zstd, 4096), 200);
  const auto zstd_bytes = read_bytes(zstd_file);
  const auto zstd_chunk = Reader(zstd_file).info().chunks.at(1).offset;
  Corrupt size{"size", zstd_bytes};
  size.bytes[zstd_chunk + 9 + 8 + 8 + 1] ^= 0x01;  // uncompressed_size
  expect_format_error(dir, size, zstd_chunk, "zstd frame holds", kRead);
  Corrupt codec{"codec", zstd_bytes};
  codec.bytes[zstd_chunk + 9 + 8 + 8 + 8 + 4 + 4 + 3] = 'x';  // "zstd" -> "zstx"
  codec.bytes.resize(summary_start(zstd_bytes));
  expect_format_error(dir, codec, zstd_chunk, "unsupported compression 'zstx'", kOpen);

  // A field that overruns its record: a Schema name longer than the record.
  Corrupt field{"field", good};
  field.bytes[first_record + 9 + 2 + 3] = 0x7F;  // high byte of the name's length
  field.bytes.resize(summary);
  expect_format_error(dir, field, first_record + 9 + 2, "field 'name'", kOpen);
}

// ---------------------------------------------------------------------------
// Files in layouts our writer does not produce

// Encodes records by hand, as a third-party writer might lay them out.
class RawFile {
 public:
  RawFile() { bytes.assign(wbi::mcap::kMagic.begin(), wbi::mcap::kMagic.end()); }
  void u8(std::uint8_t v) { bytes.push_back(v); }
  void u16(std::uint16_t v) { le(v, 2); }
  void u32(std::uint32_t v) { le(v, 4); }
  void u64(std::uint64_t v) { le(v, 8); }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  std::size_t begin(std::uint8_t opcode) {
    u8(opcode);
    u64(0);
    return bytes.size();
  }
  void end(std::size_t start) { store_u64(bytes, start - 8, bytes.size() - start); }
  std::vector<std::uint8_t> bytes;

 private:
  void le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) {
      bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
  }
};

TEST(McapLayouts, UnchunkedMessagesAndChannelsInsideAChunk) {
  RawFile f;
  auto at = f.begin(0x01);  // Header
  f.str("");
  f.str("hand");
  f.end(at);
  at = f.begin(0x03);  // Schema 1
  f.u16(1);
  f.str("S");
  f.str("omgidl");
  f.str("struct S { long x; };");
  f.end(at);
  at = f.begin(0x04);  // Channel 1
  f.u16(1);
  f.u16(1);
  f.str("loose");
  f.str("cdr");
  f.u32(0);
  f.end(at);
  for (const std::uint64_t t : {30, 10, 20}) {  // Messages outside chunks
    at = f.begin(0x05);
    f.u16(1);
    f.u32(static_cast<std::uint32_t>(t));
    f.u64(t);
    f.u64(t);
    f.u8(static_cast<std::uint8_t>(t));
    f.end(at);
  }
  // An uncompressed chunk (CRC 0: not available) holding Channel 2 and its message.
  RawFile inner;
  inner.bytes.clear();
  at = inner.begin(0x04);
  inner.u16(2);
  inner.u16(0);
  inner.str("chunked");
  inner.str("json");
  inner.u32(0);
  inner.end(at);
  at = inner.begin(0x05);
  inner.u16(2);
  inner.u32(0);
  inner.u64(15);
  inner.u64(15);
  inner.str("{}");
  inner.end(at);
  at = f.begin(0x06);
  f.u64(15);
  f.u64(15);
  f.u64(inner.bytes.size());
  f.u32(0);
  f.str("");
  f.u64(inner.bytes.size());
  f.bytes.insert(f.bytes.end(), inner.bytes.begin(), inner.bytes.end());
  f.end(at);
  at = f.begin(0x0F);  // DataEnd, no CRC
  f.u32(0);
  f.end(at);
  at = f.begin(0x02);  // Footer: no summary
  f.u64(0);
  f.u64(0);
  f.u32(0);
  f.end(at);
  f.bytes.insert(f.bytes.end(), wbi::mcap::kMagic.begin(), wbi::mcap::kMagic.end());

  TempDir dir;
  write_bytes(dir / "hand.mcap", f.bytes, f.bytes.size());
  const Reader reader(dir / "hand.mcap");
  EXPECT_FALSE(reader.info().from_summary);
  EXPECT_FALSE(reader.info().truncated);
  EXPECT_TRUE(reader.info().warnings.empty());
  EXPECT_EQ(reader.info().library, "hand");
  EXPECT_EQ(reader.info().statistics.message_count, 4u);
  EXPECT_EQ(reader.info().channels.at(2).topic, "chunked");
  std::vector<std::uint64_t> times;
  for (const auto& m : read_all(reader, Order::file)) {
    times.push_back(m.log_time);
  }
  EXPECT_EQ(times, (std::vector<std::uint64_t>{30, 10, 20, 15}));
  times.clear();
  for (const auto& m : read_all(reader, Order::log_time)) {
    times.push_back(m.log_time);
  }
  EXPECT_EQ(times, (std::vector<std::uint64_t>{10, 15, 20, 30}));
}

// ---------------------------------------------------------------------------
// Writer

TEST(McapWriter, EmptyRecording) {
  TempDir dir;
  { Writer writer(dir / "empty.mcap"); }  // the destructor closes
  const Reader reader(dir / "empty.mcap");
  EXPECT_TRUE(reader.info().from_summary);
  EXPECT_FALSE(reader.info().truncated);
  EXPECT_EQ(reader.info().statistics.message_count, 0u);
  EXPECT_EQ(reader.messages().next(), nullptr);
}

TEST(McapWriter, RejectsUnknownIdsAndUnwritablePaths) {
  TempDir dir;
  Writer writer(dir / "ids.mcap");
  EXPECT_THROW(writer.add_channel(7, "t"), std::invalid_argument);
  const std::vector<std::uint8_t> payload(8, 0);
  EXPECT_THROW(writer.write(1, 0, 0, 0, payload), std::invalid_argument);
  writer.close();
  EXPECT_THROW(writer.add_schema("T", "x"), std::logic_error);
  try {
    Writer bad(dir / "no" / "such" / "dir.mcap");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(contains(e.what(), "dir.mcap")) << e.what();
  }
}

TEST(McapWriter, MessageLargerThanAChunk) {
  TempDir dir;
  std::vector<std::uint8_t> big(3 * 1024 * 1024);
  for (std::size_t i = 0; i < big.size(); ++i) {
    big[i] = static_cast<std::uint8_t>(i * 7 / 3);
  }
  {
    Writer writer(dir / "big.mcap", options_with(Compression::lz4, 64 * 1024));
    const auto channel = writer.add_channel(0, "big", "raw");
    writer.write(channel, 0, 1, 1, big);
    writer.write(channel, 1, 2, 2, std::vector<std::uint8_t>(10, 1));
  }
  const Reader reader(dir / "big.mcap");
  const auto messages = read_all(reader, Order::file);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0].data, big);
  EXPECT_EQ(reader.info().chunks.size(), 2u);
}

TEST(McapWriter, MovedWriterAndReaderKeepWorking) {
  TempDir dir;
  std::optional<Writer> writer;
  writer.emplace(dir / "moved.mcap");
  const auto channel = writer->add_channel(0, "t", "raw");
  Writer moved(std::move(*writer));
  writer.reset();  // destroying the moved-from writer must not touch the file
  const std::vector<std::uint8_t> payload(16, 9);
  moved.write(channel, 0, 5, 5, payload);
  moved.close();

  Reader reader(dir / "moved.mcap");
  auto cursor = reader.messages();
  const Reader owner(std::move(reader));  // cursors follow the reader's state
  const auto* message = cursor.next();
  ASSERT_NE(message, nullptr);
  EXPECT_EQ(message->channel->topic, "t");
  EXPECT_EQ(message->data.size(), 16u);
  EXPECT_EQ(cursor.next(), nullptr);
  EXPECT_EQ(owner.info().statistics.message_count, 1u);
}

TEST(McapWriter, NoAllocationPerMessage) {
  TempDir dir;
  for (const auto compression : {Compression::none, Compression::lz4, Compression::zstd}) {
    Writer writer(dir / "alloc.mcap", options_with(compression, 1024 * 1024));
    const auto channel =
        writer.add_channel(writer.add_schema("T", "struct T { double x[100]; };"), "t");
    const std::vector<std::uint8_t> payload(800, 3);
    std::uint32_t sequence = 0;
    // Warm-up: one full chunk sizes the chunk buffer and the message index.
    for (; sequence < 1500; ++sequence) {
      writer.write(channel, sequence, sequence, sequence, payload);
    }
    writer.flush();
    const long before = wbi::test::allocation_count();
    for (; sequence < 2500; ++sequence) {  // 1000 messages within one chunk
      writer.write(channel, sequence, sequence, sequence, payload);
    }
    EXPECT_EQ(wbi::test::allocation_count() - before, 0)
        << wbi::mcap::compression_name(compression);
    // Across chunks: a few allocations per chunk (its index entry), none per message.
    const long across = wbi::test::allocation_count();
    for (; sequence < 30'000; ++sequence) {
      writer.write(channel, sequence, sequence, sequence, payload);
    }
    const auto chunks = writer.statistics().chunks;
    EXPECT_LT(wbi::test::allocation_count() - across, 4 * static_cast<long>(chunks) + 8)
        << wbi::mcap::compression_name(compression) << ", " << chunks << " chunks";
  }
}

}  // namespace
