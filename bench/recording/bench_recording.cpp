// MCAP writer and reader throughput on the recorder's load: 100-double (800 B)
// CDR payloads, one channel per topic, flush() every 50,000 messages (a
// recorder flushes once per second; 50,000 messages/s is its target).
//
//   BM_Write/<compression>/<sink>  sink 0: a file in the temp dir, 1: /dev/null
//                                  (writer CPU cost alone)
//   BM_Read/<compression>          all messages of a 100,000-message file, log-time order
//
// items_per_second is messages/s and bytes_per_second payload bytes/s, both in
// wall-clock time (file I/O included); the "ratio" counter is payload bytes over
// file bytes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <wbi/mcap/reader.hpp>
#include <wbi/mcap/writer.hpp>

namespace {

using wbi::mcap::Compression;

constexpr int kDoubles = 100;
constexpr int kTopics = 4;
constexpr std::uint64_t kFlushEvery = 50'000;
constexpr const char* kIdl =
    "module wbi { module msg { struct JointState { double q[100]; }; }; };\n";

Compression compression_of(std::int64_t index) { return static_cast<Compression>(index); }

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("wbi_bench_" + std::to_string(::getpid()) + "_" + name + ".mcap");
}

// CDR-like payloads: a 4-byte encapsulation header, then 100 joint positions
// of a smooth motion as an encoder of 2^-16 rad resolution reports them (quantised,
// so the low mantissa bits are zero as in real sensor data). A ring of them is
// made up front so that the benchmark times the writer, not the sine.
class Payloads {
 public:
  Payloads() : ring_(kRing, std::vector<std::uint8_t>(4 + kDoubles * sizeof(double))) {
    for (std::size_t i = 0; i < kRing; ++i) {
      ring_[i][1] = 1;  // CDR little-endian
      for (int j = 0; j < kDoubles; ++j) {
        // Joint j moves at its own frequency (incommensurate: no payload is a
        // shifted copy of another); time steps of 1 ms.
        const double t = 1e-3 * static_cast<double>(i);
        const double q = std::round(std::sin((1.0 + 0.173 * j) * t + 0.7 * j) * 65536.0) / 65536.0;
        std::memcpy(ring_[i].data() + 4 + j * sizeof(double), &q, sizeof(double));
      }
    }
  }
  const std::vector<std::uint8_t>& next(std::uint64_t i) const { return ring_[i % kRing]; }

 private:
  static constexpr std::size_t kRing = 16384;  // 13 MB: more than a chunk, no repeats within one
  std::vector<std::vector<std::uint8_t>> ring_;
};

std::vector<std::uint16_t> add_topics(wbi::mcap::Writer& writer) {
  const auto schema = writer.add_schema("wbi::msg::JointState", kIdl);
  std::vector<std::uint16_t> channels;
  for (int t = 0; t < kTopics; ++t) {
    channels.push_back(
        writer.add_channel(schema, "wbi/robot" + std::to_string(t) + "/sensors", "cdr",
                           {{"reliability", "reliable"}, {"durability", "volatile"}}));
  }
  return channels;
}

void BM_Write(benchmark::State& state) {
  const bool devnull = state.range(1) == 1;
  const auto path = devnull
                        ? std::filesystem::path("/dev/null")
                        : temp_file(wbi::mcap::compression_name(compression_of(state.range(0))));
  wbi::mcap::WriterOptions options;
  options.compression = compression_of(state.range(0));
  std::uint64_t file_bytes = 0;
  std::uint64_t payload_bytes = 0;
  std::uint64_t i = 0;
  {
    wbi::mcap::Writer writer(path, options);
    const auto channels = add_topics(writer);
    const Payloads payload;
    const std::uint64_t t0 = 1'700'000'000'000'000'000ull;
    for (auto _ : state) {
      const auto& data = payload.next(i);
      writer.write(channels[i % kTopics], static_cast<std::uint32_t>(i), t0 + i * 20'000,
                   t0 + i * 20'000 - 5'000, data);
      if (++i % kFlushEvery == 0) {
        writer.flush();
      }
    }
    writer.close();
    file_bytes = writer.statistics().file_bytes;
    payload_bytes = writer.statistics().payload_bytes;
  }
  if (!devnull) {
    std::filesystem::remove(path);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(i));
  state.SetBytesProcessed(static_cast<std::int64_t>(payload_bytes));
  state.counters["ratio"] =
      file_bytes > 0 ? static_cast<double>(payload_bytes) / static_cast<double>(file_bytes) : 0;
}
BENCHMARK(BM_Write)
    ->ArgsProduct({{static_cast<int>(Compression::none), static_cast<int>(Compression::lz4),
                    static_cast<int>(Compression::zstd)},
                   {0, 1}})
    ->ArgNames({"compression", "devnull"})
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(1.0)
    ->UseRealTime();

void BM_Read(benchmark::State& state) {
  const auto path =
      temp_file(std::string("read_") + wbi::mcap::compression_name(compression_of(state.range(0))));
  constexpr std::uint64_t kMessages = 100'000;
  {
    wbi::mcap::WriterOptions options;
    options.compression = compression_of(state.range(0));
    wbi::mcap::Writer writer(path, options);
    const auto channels = add_topics(writer);
    const Payloads payload;
    for (std::uint64_t i = 0; i < kMessages; ++i) {
      writer.write(channels[i % kTopics], static_cast<std::uint32_t>(i), i * 20'000, i * 20'000,
                   payload.next(i));
    }
  }
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;
  for (auto _ : state) {
    const wbi::mcap::Reader reader(path);
    auto cursor = reader.messages(wbi::mcap::Order::log_time);
    while (const auto* message = cursor.next()) {
      bytes += message->data.size();
      ++messages;
    }
  }
  std::filesystem::remove(path);
  state.SetItemsProcessed(static_cast<std::int64_t>(messages));
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
BENCHMARK(BM_Read)
    ->Arg(static_cast<int>(Compression::none))
    ->Arg(static_cast<int>(Compression::lz4))
    ->Arg(static_cast<int>(Compression::zstd))
    ->ArgName("compression")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
