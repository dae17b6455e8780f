// Issue 8, item 5: a file written by `wbi record` from live publisher
// processes is read by independent implementations from the npm registry —
// the TypeScript @mcap/core indexed reader (CRCs checked; fzstd decompresses
// the recorder's zstd chunks) and Foxglove's OMG-IDL parser and CDR decoder
// (@foxglove/omgidl-parser, @foxglove/omgidl-serialization), given only the
// IDL text stored in each Schema record — and every message decodes to the
// values that were published.
//
// Two talker processes (interop_talker.cpp) publish a robot description, sensor
// samples and state estimates each: strings, an enum, a boolean, nested
// structs, sequences of doubles and of structs, fixed arrays, 32- and 64-bit
// integers. Needs node, npm and the packages in wbi's npm cache
// (scripts/install-deps; the test stays offline): when one is missing the
// test is skipped with the reason, never failed.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "interop_pattern.hpp"
#include "npm_packages.hpp"
#include "record_play_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

constexpr std::uint64_t kCount = 40;  // sensor samples and state estimates per talker

// Decodes every message of FILE with the schema's IDL text; one JSON object per
// line in log-time order: {topic, type, sequence, publish_time, value}.
constexpr const char* kDecodeScript = R"js(
const fs = require("fs");
const { McapIndexedReader } = require("@mcap/core");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const fzstd = require("fzstd");
const lz4 = require("lz4js");

const decompressHandlers = {
  zstd: (data, size) => fzstd.decompress(data, new Uint8Array(Number(size))),
  lz4: (data, size) => Uint8Array.from(lz4.decompress(data, Number(size))),
};
// JSON has no 64-bit integers: decimal strings; typed arrays as plain arrays.
const plain = (key, value) =>
  typeof value === "bigint" ? value.toString() : ArrayBuffer.isView(value) ? Array.from(value) : value;

async function main(file, out) {
  const bytes = fs.readFileSync(file);
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  const decoders = new Map();
  for (const [id, schema] of reader.schemasById) {
    if (schema.encoding !== "omgidl") throw new Error(`schema ${schema.name}: encoding ${schema.encoding}`);
    const idl = new TextDecoder().decode(schema.data);
    decoders.set(id, new MessageReader(schema.name, parseIDL(idl)));
  }
  const lines = [];
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    const channel = reader.channelsById.get(m.channelId);
    if (channel.messageEncoding !== "cdr") throw new Error(`${channel.topic}: ${channel.messageEncoding}`);
    const value = decoders.get(channel.schemaId).readMessage(new Uint8Array(m.data));
    lines.push(JSON.stringify({
      topic: channel.topic,
      type: reader.schemasById.get(channel.schemaId).name,
      sequence: m.sequence,
      publish_time: m.publishTime,
      value,
    }, plain));
  }
  fs.writeFileSync(out, lines.join("\n") + "\n");
  console.log(`${file}: ${lines.length} messages decoded`);
}
main(process.argv[2], process.argv[3]).catch((e) => { console.error(`decode failed: ${e.stack || e}`); process.exit(1); });
)js";

// What the talker of `robot` published as the index-th message on `kind`.
nlohmann::json expected_value(const std::string& robot, const std::string& kind,
                              std::uint64_t index) {
  if (kind == "description") {
    wbi::msg::RobotDescription description;
    wbi::test::fill_description(description, robot);
    return wbi::test::to_json(description);
  }
  if (kind == "sensors") {
    wbi::msg::SensorSample sample;
    wbi::test::fill_sensors(sample, robot, index);
    return wbi::test::to_json(sample);
  }
  wbi::msg::StateEstimate state;
  wbi::test::fill_state(state, robot, index);
  return wbi::test::to_json(state);
}

const std::map<std::string, std::string> kTypeOfKind{{"description", "wbi::msg::RobotDescription"},
                                                     {"sensors", "wbi::msg::SensorSample"},
                                                     {"state", "wbi::msg::StateEstimate"}};

TEST(RecordInterop, FoxgloveDecodesEveryRecordedMessageToThePublishedValues) {
  wbi::test::TempDir dir;
  const auto npm = wbi::test::install_npm_packages(
      dir.path(), {"@mcap/core@^2", "fzstd@^0.1", "lz4js@^0.2", "@foxglove/omgidl-parser@^1",
                   "@foxglove/omgidl-serialization@^1"});
  if (npm.node.empty()) {
    GTEST_SKIP() << npm.skip_reason;
  }
  const auto recording = dir / "live.mcap";
  const std::vector<std::string> robots{"interop_a", "interop_b"};
  {
    ChildProcess recorder(wbi::test::wbi_program(),
                          {"record", "-o", recording.string(), "wbi/interop_.*"});
    ASSERT_TRUE(recorder.wait_for_output("recording to", 20s)) << recorder.output();
    const auto talker = wbi::test::binary_dir() / "tests" / "wbi_test_interop_talker";
    ChildProcess first(talker, {robots[0], std::to_string(kCount)});
    ChildProcess second(talker, {robots[1], std::to_string(kCount)});
    ASSERT_EQ(first.wait(60s), 0) << first.output() << recorder.output();
    ASSERT_EQ(second.wait(60s), 0) << second.output() << recorder.output();
    ASSERT_EQ(recorder.stop(SIGINT, 20s), 0) << recorder.output();
  }

  const auto decoded_file = dir / "decoded.jsonl";
  const auto script = dir / "decode.cjs";
  std::ofstream(script) << kDecodeScript;
  ChildProcess decode(npm.node, {script.string(), recording.string(), decoded_file.string()});
  ASSERT_EQ(decode.wait(60s), 0) << decode.output();

  std::map<std::string, std::uint64_t> count_by_topic;
  std::ifstream lines(decoded_file);
  std::size_t decoded = 0;
  for (std::string line; std::getline(lines, line);) {
    const auto message = nlohmann::json::parse(line);
    const std::string topic = message.at("topic");
    // wbi/<robot>/<kind>
    const auto robot_end = topic.find('/', 4);
    const std::string robot = topic.substr(4, robot_end - 4);
    const std::string kind = topic.substr(robot_end + 1);
    ASSERT_TRUE(kTypeOfKind.count(kind)) << line;
    EXPECT_EQ(message.at("type"), kTypeOfKind.at(kind)) << topic;
    const std::uint64_t index = count_by_topic[topic]++;
    EXPECT_EQ(message.at("sequence"), index) << topic;
    const auto expected = expected_value(robot, kind, index);
    EXPECT_EQ(message.at("value"), expected) << topic << " message " << index;
    EXPECT_EQ(message.at("publish_time"), expected.at("header").at("stamp_ns"))
        << topic << ": publish time = Header.stamp_ns";
    ++decoded;
  }
  std::map<std::string, std::uint64_t> expected_counts;
  for (const auto& robot : robots) {
    expected_counts["wbi/" + robot + "/description"] = 1;
    expected_counts["wbi/" + robot + "/sensors"] = kCount;
    expected_counts["wbi/" + robot + "/state"] = kCount;
  }
  EXPECT_EQ(count_by_topic, expected_counts);
  EXPECT_EQ(decoded, 2 * (1 + 2 * kCount));
}

}  // namespace
