// Interoperability: files written by wbi::mcap (uncompressed, lz4, zstd) are read
// by an independent implementation, the TypeScript @mcap/core library from the
// npm registry, run with node. Both its indexed reader (summary, chunk and
// message indexes, CRCs) and its stream reader (every record in file order,
// chunk CRCs) must return every message with its topic, type, sequence, times
// and payload bytes. fzstd and lz4js (pure JavaScript) decompress the chunks,
// so the decompressors are independent of ours too.
//
// Needs node, npm and the packages in wbi's npm cache (scripts/install-deps
// puts them there; the test itself stays offline): when one is missing the
// test is skipped with the reason, never failed.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "mcap_samples.hpp"
#include "npm_packages.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;
using wbi::test::SampleMessage;

// The line check.cjs prints for a message.
std::string line_of(const SampleMessage& m) {
  static const char* const kHex = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * m.data.size());
  for (const std::uint8_t byte : m.data) {
    hex += kHex[byte >> 4];
    hex += kHex[byte & 0xF];
  }
  return m.topic + " " + m.type + " " + std::to_string(m.sequence) + " " +
         std::to_string(m.log_time) + " " + std::to_string(m.publish_time) + " " + hex;
}

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::vector<std::string> lines;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    lines.push_back(line);
  }
  return lines;
}

void expect_lines(const std::filesystem::path& file, const std::vector<SampleMessage>& want) {
  const auto got = lines_of(file);
  ASSERT_EQ(got.size(), want.size()) << file;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i], line_of(want[i])) << file << ", message " << i;
  }
}

// Reads FILE with @mcap/core twice and writes FILE.indexed.txt (log-time order)
// and FILE.stream.txt (file order), one line per message.
constexpr const char* kCheckScript = R"js(
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const fzstd = require("fzstd");
const lz4 = require("lz4js");

const decompressHandlers = {
  zstd: (data, size) => fzstd.decompress(data, new Uint8Array(Number(size))),
  lz4: (data, size) => Uint8Array.from(lz4.decompress(data, Number(size))),
};
const hex = (data) => Buffer.from(data.buffer, data.byteOffset, data.byteLength).toString("hex");
const line = (channel, schema, m) =>
  `${channel.topic} ${schema ? schema.name : ""} ${m.sequence} ${m.logTime} ${m.publishTime} ${hex(m.data)}`;

async function main(file) {
  const bytes = fs.readFileSync(file);
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  const indexed = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  if (indexed.header.profile !== "wbi") throw new Error(`profile ${indexed.header.profile}`);
  for (const schema of indexed.schemasById.values()) {
    if (schema.name !== "raw" && schema.encoding !== "omgidl") throw new Error(`schema ${schema.name}`);
  }
  const out = [];
  for await (const m of indexed.readMessages({ validateCrcs: true })) {
    const channel = indexed.channelsById.get(m.channelId);
    out.push(line(channel, indexed.schemasById.get(channel.schemaId), m));
  }
  if (BigInt(out.length) !== indexed.statistics.messageCount) throw new Error("statistics count");
  fs.writeFileSync(file + ".indexed.txt", out.join("\n") + "\n");

  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  stream.append(bytes);
  const schemas = new Map();
  const channels = new Map();
  const lines = [];
  for (let record; (record = stream.nextRecord()); ) {
    if (record.type === "Schema") schemas.set(record.id, record);
    if (record.type === "Channel") channels.set(record.id, record);
    if (record.type === "Message") {
      const channel = channels.get(record.channelId);
      lines.push(line(channel, schemas.get(channel.schemaId), record));
    }
  }
  if (!stream.done()) throw new Error("the stream reader did not reach the footer");
  fs.writeFileSync(file + ".stream.txt", lines.join("\n") + "\n");
  console.log(`${file}: ${out.length} messages`);
}
main(process.argv[2]).catch((e) => { console.error(`check failed: ${e.stack || e}`); process.exit(1); });
)js";

TEST(McapInterop, McapCoreReadsOurFiles) {
  wbi::test::TempDir dir;
  const auto npm =
      wbi::test::install_npm_packages(dir.path(), {"@mcap/core@^2", "fzstd@^0.1", "lz4js@^0.2"});
  if (npm.node.empty()) {
    GTEST_SKIP() << npm.skip_reason;
  }
  const auto script = dir / "check.cjs";
  std::ofstream(script) << kCheckScript;

  for (const auto compression :
       {wbi::mcap::Compression::none, wbi::mcap::Compression::lz4, wbi::mcap::Compression::zstd}) {
    SCOPED_TRACE(wbi::mcap::compression_name(compression));
    const auto file =
        dir / (std::string("run_") + wbi::mcap::compression_name(compression) + ".mcap");
    wbi::mcap::WriterOptions options;
    options.compression = compression;
    options.chunk_size = 64 * 1024;
    const auto written = wbi::test::write_sample(file, options, 2000);

    ChildProcess check(npm.node, {script.string(), file.string()});
    const auto code = check.wait(60s);
    ASSERT_EQ(code, 0) << check.output();
    expect_lines(file.string() + ".indexed.txt", wbi::test::by_log_time(written));
    expect_lines(file.string() + ".stream.txt", written);
  }
}

}  // namespace
