// `wbi bag info` as a user meets it: text and JSON of a good recording, a
// truncated one (what could be read, then one line on what was lost, exit 1), an
// empty, a foreign and a corrupt one (one line, exit 1). Runs build*/bin/wbi; skipped while the
// verb is not registered there.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "mcap_samples.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

struct Run {
  int code;
  std::string output;  // stdout and stderr interleaved
};

Run wbi_cli(const std::vector<std::string>& args) {
  ChildProcess process(wbi::test::binary_dir() / "bin" / "wbi", args);
  const auto code = process.wait(30s);
  return {code.value_or(-1), process.output()};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The JSON object in the output (lines on stderr may precede or follow it).
nlohmann::json json_of(const std::string& output) {
  const auto start = output.find("{\n");
  const auto end = output.rfind("\n}");
  if (start == std::string::npos || end == std::string::npos || end < start) {
    ADD_FAILURE() << "no JSON object in: " << output;
    return {};
  }
  return nlohmann::json::parse(output.substr(start, end + 2 - start));
}

class BagCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // `wbi bag` is part of this build: a failing --help is a failure, not a skip.
    const auto help = wbi_cli({"bag", "--help"});
    ASSERT_EQ(help.code, 0) << wbi::test::binary_dir() / "bin/wbi"
                            << " bag --help\n"
                            << help.output;
    wbi::mcap::WriterOptions options;
    options.chunk_size = 32 * 1024;
    written_ = wbi::test::write_sample(file_, options, 5000);
  }

  // The recording's span as bag info computes it.
  double duration_s() const {
    const auto sorted = wbi::test::by_log_time(written_);
    return static_cast<double>(sorted.back().log_time - sorted.front().log_time) / 1e9;
  }

  wbi::test::TempDir dir_;
  std::filesystem::path file_ = dir_ / "run.mcap";
  std::vector<wbi::test::SampleMessage> written_;
};

TEST_F(BagCli, InfoPrintsDurationTopicsAndCounts) {
  const auto run = wbi_cli({"bag", "info", file_.string()});
  ASSERT_EQ(run.code, 0) << run.output;
  std::array<char, 64> duration{};
  std::snprintf(duration.data(), duration.size(), "duration:     %.3f s", duration_s());
  for (const std::string& part :
       {std::string("messages:     5000"), std::string(duration.data()),
        std::string("compression:  zstd"), std::string("topics:       5"),
        std::string("index:        summary"),
        std::string("start:        2023-11-14 22:13:19.997700000 UTC  (1699999999997700000 ns)"),
        std::string("wbi/arm/sensors"), std::string("wbi::msg::JointState"),
        std::string("1000 msgs"), std::string("wbi/log")}) {
    EXPECT_TRUE(contains(run.output, part)) << part << "\n" << run.output;
  }
  EXPECT_FALSE(contains(run.output, "warning")) << run.output;
}

TEST_F(BagCli, InfoJson) {
  const auto run = wbi_cli({"bag", "info", file_.string(), "--json"});
  ASSERT_EQ(run.code, 0) << run.output;
  const auto json = json_of(run.output);
  EXPECT_EQ(json["messages"], 5000);
  EXPECT_NEAR(json["duration_s"].get<double>(), duration_s(), 1e-9);
  EXPECT_EQ(json["compression"], "zstd");
  EXPECT_EQ(json["truncated"], false);
  ASSERT_EQ(json["topics"].size(), 5u);
  std::map<std::string, nlohmann::json> topics;
  for (const auto& topic : json["topics"]) {
    topics[topic["name"]] = topic;
    EXPECT_EQ(topic["count"], 1000) << topic;
  }
  EXPECT_EQ(topics.at("wbi/arm/sensors")["type"], "wbi::msg::JointState");
  EXPECT_EQ(topics.at("wbi/arm/sensors")["metadata"]["reliability"], "best_effort");
  EXPECT_EQ(topics.at("wbi/arm/commands")["type"], "wbi::msg::Command");
  EXPECT_EQ(topics.at("wbi/log")["type"], "");
  EXPECT_NEAR(topics.at("wbi/humanoid/sensors")["rate_hz"].get<double>(), 1000 / duration_s(),
              1e-6);
}

// The lines of `output` that start with `prefix`.
std::vector<std::string> lines_starting(const std::string& output, const std::string& prefix) {
  std::vector<std::string> found;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) == 0) {
      found.push_back(line);
    }
  }
  return found;
}

TEST_F(BagCli, TruncatedFilePrintsWhatWasReadThenOneLineOnWhatWasLost) {
  const auto bytes = wbi::test::read_bytes(file_);
  const auto cut = dir_ / "cut.mcap";
  wbi::test::write_bytes(cut, bytes, bytes.size() / 2);
  const auto run = wbi_cli({"bag", "info", cut.string(), "--json"});
  EXPECT_EQ(run.code, 1) << run.output;
  const auto errors = lines_starting(run.output, "wbi bag: ");
  ASSERT_EQ(errors.size(), 1u) << run.output;
  EXPECT_TRUE(contains(errors[0], "wbi bag: " + cut.string() + ": file truncated")) << errors[0];
  EXPECT_FALSE(contains(run.output, "wbi bag: warning")) << run.output;
  const auto json = json_of(run.output);
  EXPECT_GT(json["messages"].get<int>(), 1000);
  EXPECT_LT(json["messages"].get<int>(), 5000);
  EXPECT_EQ(json["truncated"], true);

  const auto text = wbi_cli({"bag", "info", cut.string()});
  EXPECT_EQ(text.code, 1) << text.output;
  EXPECT_TRUE(contains(text.output, "index:        none (data section scanned)")) << text.output;
}

TEST_F(BagCli, CutMidChunkSaysWhichMessagesAreLostAndWhatIsReadable) {
  const wbi::mcap::Reader whole(file_);
  const auto& chunks = whole.info().chunks;
  ASSERT_GE(chunks.size(), 3u);
  const auto& lost = chunks[chunks.size() / 2];
  const std::uint64_t end = lost.offset + lost.length / 2;
  const auto cut = dir_ / "mid_chunk.mcap";
  wbi::test::write_bytes(cut, wbi::test::read_bytes(file_), end);
  const wbi::mcap::Reader part(cut);
  const auto readable = part.info().statistics.message_count;
  ASSERT_GT(readable, 0u);
  ASSERT_LT(readable, 5000u);

  const auto run = wbi_cli({"bag", "info", cut.string()});
  EXPECT_EQ(run.code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "messages:     " + std::to_string(readable))) << run.output;
  const auto errors = lines_starting(run.output, "wbi bag: ");
  ASSERT_EQ(errors.size(), 1u) << run.output;
  const std::string& line = errors[0];
  for (const std::string& part_text : std::vector<std::string>{
           "wbi bag: " + cut.string() + ": file truncated: it ends at byte " + std::to_string(end) +
               " inside a Chunk record that starts at byte " + std::to_string(lost.offset),
           "lost: its last " + std::to_string(lost.offset + lost.length - end) +
               " bytes, so all its messages, logged from ",
           "and whatever was recorded after it",
           "readable: " + std::to_string(readable) + " messages in " + std::to_string(lost.offset) +
               " bytes"}) {
    EXPECT_TRUE(contains(line, part_text)) << part_text << "\n" << line;
  }
  std::array<char, 32> span{};
  std::snprintf(span.data(), span.size(), "(%.3f s)",
                static_cast<double>(lost.message_end_time - lost.message_start_time) / 1e9);
  EXPECT_TRUE(contains(line, span.data())) << span.data() << "\n" << line;

  const auto json_run = wbi_cli({"bag", "info", cut.string(), "--json"});
  EXPECT_EQ(json_run.code, 1) << json_run.output;
  const auto truncation = json_of(json_run.output)["truncation"];
  EXPECT_EQ(truncation["readable_bytes"], lost.offset) << truncation;
  EXPECT_EQ(truncation["cut_record"], "Chunk") << truncation;
  EXPECT_EQ(truncation["cut_record_offset"], lost.offset) << truncation;
  EXPECT_EQ(truncation["cut_record_bytes"], lost.length) << truncation;
  EXPECT_EQ(truncation["lost_start_ns"], lost.message_start_time) << truncation;
  EXPECT_EQ(truncation["lost_end_ns"], lost.message_end_time) << truncation;
}

TEST_F(BagCli, EmptyFileIsAOneLineError) {
  const auto empty = dir_ / "empty.mcap";
  wbi::test::write_bytes(empty, {}, 0);
  const auto run = wbi_cli({"bag", "info", empty.string()});
  EXPECT_EQ(run.code, 1);
  EXPECT_EQ(run.output,
            "wbi bag: " + empty.string() + ": empty file (0 bytes), not an MCAP recording\n");
}

TEST_F(BagCli, AFileWithoutTheMagicIsAOneLineError) {
  const auto text = dir_ / "notes.mcap";
  const std::string words = "not a recording, just some words\n";
  wbi::test::write_bytes(text, std::vector<std::uint8_t>(words.begin(), words.end()), words.size());
  const auto run = wbi_cli({"bag", "info", text.string()});
  EXPECT_EQ(run.code, 1);
  EXPECT_EQ(run.output, "wbi bag: " + text.string() + ": byte 0: not an MCAP file (bad magic)\n");
}

TEST_F(BagCli, CorruptFileIsAOneLineError) {
  auto bytes = wbi::test::read_bytes(file_);
  bytes[bytes.size() - 100] ^= 0xFF;  // in the summary: its CRC no longer matches
  const auto bad = dir_ / "bad.mcap";
  wbi::test::write_bytes(bad, bytes, bytes.size());
  const auto run = wbi_cli({"bag", "info", bad.string()});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "wbi bag: " + bad.string() + ": byte ")) << run.output;
  EXPECT_TRUE(contains(run.output, "summary section CRC mismatch")) << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;

  bytes = wbi::test::read_bytes(file_);
  bytes[0] = 'X';
  wbi::test::write_bytes(bad, bytes, bytes.size());
  const auto magic = wbi_cli({"bag", "info", bad.string(), "--json"});
  EXPECT_EQ(magic.code, 1);
  EXPECT_TRUE(contains(magic.output, "byte 0: not an MCAP file (bad magic)")) << magic.output;
}

TEST_F(BagCli, PlayRefusesWhatIsNotARecordingInOneLine) {
  const auto empty = dir_ / "empty.mcap";
  wbi::test::write_bytes(empty, {}, 0);
  const auto run = wbi_cli({"play", empty.string()});
  EXPECT_EQ(run.code, 1);
  EXPECT_EQ(run.output,
            "wbi play: " + empty.string() + ": empty file (0 bytes), not an MCAP recording\n");

  const auto text = dir_ / "notes.mcap";
  const std::string words = "not a recording, just some words\n";
  wbi::test::write_bytes(text, std::vector<std::uint8_t>(words.begin(), words.end()), words.size());
  const auto magic = wbi_cli({"play", text.string()});
  EXPECT_EQ(magic.code, 1);
  EXPECT_EQ(magic.output,
            "wbi play: " + text.string() + ": byte 0: not an MCAP file (bad magic)\n");
}

TEST_F(BagCli, PlayOfATruncatedFilePlaysWhatIsReadableThenSaysWhatWasLost) {
  const auto bytes = wbi::test::read_bytes(file_);
  const auto cut = dir_ / "cut.mcap";
  wbi::test::write_bytes(cut, bytes, bytes.size() / 2);
  const auto run = wbi_cli({"play", cut.string(), "--rate", "100"});
  EXPECT_EQ(run.code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "played ")) << run.output;
  const auto errors = lines_starting(run.output, "wbi play: ");
  ASSERT_EQ(errors.size(), 1u) << run.output;
  EXPECT_TRUE(contains(errors[0], "wbi play: " + cut.string() + ": file truncated")) << errors[0];
}

TEST_F(BagCli, VerifyReadsEveryChunk) {
  auto bytes = wbi::test::read_bytes(file_);
  // A byte of the first MessageIndex record: only the data-section CRC covers it.
  const wbi::mcap::Reader reader(file_);
  const auto& chunk = reader.info().chunks.at(0);
  bytes[chunk.offset + chunk.length + 12] ^= 0xFF;
  const auto bad = dir_ / "index.mcap";
  wbi::test::write_bytes(bad, bytes, bytes.size());
  EXPECT_EQ(wbi_cli({"bag", "info", bad.string()}).code, 0);
  const auto run = wbi_cli({"bag", "info", bad.string(), "--verify"});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "data section CRC mismatch")) << run.output;
  EXPECT_EQ(wbi_cli({"bag", "info", file_.string(), "--verify"}).code, 0);
}

TEST_F(BagCli, UsageErrors) {
  auto run = wbi_cli({"bag", "info"});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "see 'wbi bag --help'")) << run.output;
  run = wbi_cli({"bag", "frobnicate"});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "unknown sub-command 'frobnicate'")) << run.output;
  run = wbi_cli({"bag", "info", (dir_ / "missing.mcap").string()});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "missing.mcap: cannot open: No such file or directory"))
      << run.output;
  run = wbi_cli({"bag", "info", "--help"});
  EXPECT_EQ(run.code, 0);
  EXPECT_TRUE(contains(run.output, "usage: wbi bag info FILE")) << run.output;
}

}  // namespace
