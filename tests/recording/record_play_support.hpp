// Helpers of the record/play tests: running `wbi`, the CDR bytes of the
// talker's pattern samples, and a synthetic recording with exact timing.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>
#include <wbi/dds/cdr.hpp>

#include <wbi/msg/sensorsPubSubTypes.h>
#include <wbi/mcap/reader.hpp>
#include <wbi/mcap/writer.hpp>
#include <wbi/msg/idl_text.hpp>

#include "child_process.hpp"
#include "mcap_samples.hpp"
#include "sample_pattern.hpp"
#include "test_support.hpp"

namespace wbi::test {

inline std::filesystem::path wbi_program() { return binary_dir() / "bin" / "wbi"; }
inline std::filesystem::path talker_program() { return binary_dir() / "tests" / "wbi_test_talker"; }

struct CliRun {
  int code;
  std::string output;  // stdout and stderr interleaved
};

inline CliRun run_wbi(const std::vector<std::string>& args,
                      std::chrono::milliseconds timeout = std::chrono::seconds(60)) {
  ChildProcess process(wbi_program(), args);
  const auto code = process.wait(timeout);
  return {code.value_or(-1), process.output()};
}

// The serialized bytes (encapsulation included) of the talker's sample `seq`.
inline std::vector<std::uint8_t> pattern_cdr(const std::string& robot, std::uint64_t seq) {
  msg::SensorSample sample;
  fill_pattern(sample, robot, seq);
  auto cdr = dds::encode_cdr(sample);
  if (cdr.empty()) {
    ADD_FAILURE() << "cannot serialize sample " << seq;
  }
  return cdr;
}

// Per topic, the messages of a file in log-time order.
inline std::map<std::string, std::vector<SampleMessage>> messages_by_topic(
    const std::filesystem::path& file) {
  const mcap::Reader reader(file);
  std::map<std::string, std::vector<SampleMessage>> by_topic;
  for (auto& message : read_all(reader, mcap::Order::log_time)) {
    by_topic[message.topic].push_back(std::move(message));
  }
  return by_topic;
}

// A unique scratch file name for this test process.
inline std::filesystem::path scratch_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("wbi_record_play_" + std::to_string(getpid()) + "_" + name);
}

// A recording of pattern sensor samples on wbi/<robot>/sensors for each robot,
// `count` per robot, `period` apart (robots interleaved), QoS of wbi.stream.
inline void write_pattern_recording(const std::filesystem::path& file,
                                    const std::vector<std::string>& robots, std::uint64_t count,
                                    std::chrono::nanoseconds period) {
  mcap::Writer writer(file);
  const std::string type = "wbi::msg::SensorSample";
  const auto schema = writer.add_schema(type, msg::idl_text_for(type));
  std::vector<std::uint16_t> channels;
  for (const auto& robot : robots) {
    channels.push_back(writer.add_channel(schema, "wbi/" + robot + "/sensors", "cdr",
                                          {{"reliability", "reliable"},
                                           {"durability", "transient_local"},
                                           {"history_depth", "1"},
                                           {"qos_profile", "wbi.stream"}}));
  }
  const std::uint64_t start = 1'700'000'000'000'000'000ULL;
  for (std::uint64_t seq = 0; seq < count; ++seq) {
    for (std::size_t r = 0; r < robots.size(); ++r) {
      const auto log_time = start + seq * static_cast<std::uint64_t>(period.count()) + r;
      writer.write(channels[r], static_cast<std::uint32_t>(seq), log_time, seq * 1'000'000,
                   pattern_cdr(robots[r], seq));
    }
  }
  writer.close();
}

}  // namespace wbi::test
