// Sample MCAP files for the recording tests: several schemas and channels,
// payloads of varied size and compressibility, log times that are not in file
// order. Each writer call is recorded so that tests can compare what they read.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include <wbi/mcap/reader.hpp>
#include <wbi/mcap/writer.hpp>

namespace wbi::test {

// A message as written or read.
struct SampleMessage {
  std::string topic;
  std::string type;  // schema name, "" without schema
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::vector<std::uint8_t> data;

  bool operator==(const SampleMessage&) const = default;
};

inline SampleMessage copy_of(const mcap::MessageView& view) {
  return {view.channel->topic, view.schema != nullptr ? view.schema->name : "",
          view.sequence,       view.log_time,
          view.publish_time,   {view.data.begin(), view.data.end()}};
}

inline std::vector<SampleMessage> read_all(const mcap::Reader& reader, mcap::Order order) {
  std::vector<SampleMessage> out;
  auto cursor = reader.messages(order);
  while (const auto* message = cursor.next()) {
    out.push_back(copy_of(*message));
  }
  return out;
}

// The written messages in log-time order (ties in file order).
inline std::vector<SampleMessage> by_log_time(std::vector<SampleMessage> messages) {
  std::stable_sort(
      messages.begin(), messages.end(),
      [](const SampleMessage& a, const SampleMessage& b) { return a.log_time < b.log_time; });
  return messages;
}

// A fresh directory under the system temp dir (or under `base`), removed on
// destruction.
class TempDir {
 public:
  explicit TempDir(const std::filesystem::path& base = std::filesystem::temp_directory_path()) {
    static std::atomic<int> counter{0};
    path_ =
        base / ("wbi_mcap_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// /dev/shm when there is one (tmpfs: thousands of small files are cheap there),
// else the temp dir.
inline std::filesystem::path fast_temp_base() {
  std::error_code error;
  if (std::filesystem::is_directory("/dev/shm", error) && ::access("/dev/shm", W_OK) == 0) {
    return "/dev/shm";
  }
  return std::filesystem::temp_directory_path();
}

inline std::vector<std::uint8_t> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Writes the first `count` bytes to a new file (an existing one is removed
// first: ext4 flushes a file truncated and rewritten in place on close, which
// makes thousands of rewrites slow).
inline void write_bytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes,
                        std::size_t count) {
  std::filesystem::remove(path);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(count));
}

inline constexpr const char* kJointStateIdl =
    "module wbi { module msg {\n"
    "  struct JointState { double position[100]; };\n"
    "}; };\n";
inline constexpr const char* kCommandIdl =
    "module wbi { module msg {\n"
    "  struct Command { unsigned long long stamp; sequence<double> tau; };\n"
    "}; };\n";

// Writes `count` messages over five channels (two share a schema, one has no
// schema) and returns them in file order. Channel 3 lags 2.5 ms behind, so
// file order is not log-time order. Channel 1 carries 100 doubles of a sine,
// the others 0..1600 pseudo-random bytes; `small` makes that 4 doubles and 0..64
// bytes.
inline std::vector<SampleMessage> write_sample(const std::filesystem::path& path,
                                               mcap::WriterOptions options, int count,
                                               bool flush_every_100 = false, bool small = false) {
  const int doubles = small ? 4 : 100;
  const std::uint64_t max_random = small ? 64 : 1600;
  mcap::Writer writer(path, std::move(options));
  const auto joint_state = writer.add_schema("wbi::msg::JointState", kJointStateIdl);
  const auto command = writer.add_schema("wbi::msg::Command", kCommandIdl);
  EXPECT_EQ(writer.add_schema("wbi::msg::JointState", kJointStateIdl),
            joint_state);  // deduplicated
  const std::vector<std::uint8_t> raw_schema{0, 1, 2, 3};
  const auto raw = writer.add_schema("raw", "custom", raw_schema);
  struct Topic {
    std::uint16_t channel;
    std::string name;
    std::string type;
  };
  const std::vector<Topic> topics{
      {writer.add_channel(joint_state, "wbi/arm/sensors", "cdr",
                          {{"reliability", "best_effort"}, {"history_depth", "1"}}),
       "wbi/arm/sensors", "wbi::msg::JointState"},
      {writer.add_channel(command, "wbi/arm/commands"), "wbi/arm/commands", "wbi::msg::Command"},
      {writer.add_channel(joint_state, "wbi/humanoid/sensors"), "wbi/humanoid/sensors",
       "wbi::msg::JointState"},
      {writer.add_channel(0, "wbi/log", "json"), "wbi/log", ""},
      {writer.add_channel(raw, "wbi/raw", "custom"), "wbi/raw", "raw"},
  };
  std::vector<SampleMessage> written;
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  const auto next_random = [&] {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  const std::uint64_t base = 1'700'000'000'000'000'000ull;
  for (int i = 0; i < count; ++i) {
    const std::size_t k = static_cast<std::size_t>(i) % topics.size();
    SampleMessage m;
    m.topic = topics[k].name;
    m.type = topics[k].type;
    m.sequence = static_cast<std::uint32_t>(i / static_cast<int>(topics.size()));
    m.log_time = base + static_cast<std::uint64_t>(i) * 100'000 - (k == 2 ? 2'500'000 : 0);
    m.publish_time = m.log_time - 40'000;
    if (k == 0) {
      m.data.resize(4 + static_cast<std::size_t>(doubles) * sizeof(double));
      for (int j = 0; j < doubles; ++j) {
        const double value = std::sin(0.01 * (i + j));
        std::memcpy(m.data.data() + 4 + j * sizeof(double), &value, sizeof(double));
      }
    } else {
      m.data.resize(next_random() % max_random);
      for (auto& byte : m.data) {
        byte = static_cast<std::uint8_t>(next_random());
      }
    }
    writer.write(topics[k].channel, m.sequence, m.log_time, m.publish_time, m.data);
    written.push_back(std::move(m));
    if (flush_every_100 && i % 100 == 99) {
      writer.flush();
    }
  }
  writer.close();
  return written;
}

}  // namespace wbi::test
