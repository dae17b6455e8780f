// End-to-end figures of `wbi record` and `wbi play` (wbi::recording), over
// real DDS between two participants of this process:
//
//   sustained  N topics of 100-double SensorSamples at 1 kHz each for D s:
//              messages/s recorded, samples lost (published - recorded) and
//              recorder queue drops (the recorder's own loss counter)
//   max_rate   the same payloads written as fast as the writers take them
//              (wbi.command QoS, depth 8) on N topics for D s
//   play       a 1 kHz recording played to a subscriber: the error of each
//              inter-arrival interval against 1 ms, p50 / p99 / max, and of
//              the intervals between writes (DDS source timestamps); with
//              normal scheduling, at `wbi play --realtime-priority 20`, and at
//              that with `--spin-us 900`; and at `--rate 2` (against 0.5 ms).
//              span_ratio: the arrivals' span over the recorded one / rate
//              (1 when the player keeps the recorded timing; test_record_play
//              only checks that it never plays faster)
//
// The streams' QoS is the built-in one (reliable) unless WBI_QOS_FILE names
// another, e.g. deploy/qos_realtime.xml (best effort); the JSON says which.
//
// usage: wbi_bench_record_play [--duration S] [--topics N,N,...] [--json FILE]
// Prints one JSON object (also to FILE with --json).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/mcap/reader.hpp>
#include <wbi/mcap/writer.hpp>
#include <wbi/msg/idl_text.hpp>
#include <wbi/recording/player.hpp>
#include <wbi/recording/recorder.hpp>

#include "../common/percentile.hpp"

using wbi::bench::percentile;

namespace {

using Clock = std::chrono::steady_clock;
using Sample = wbi::msg::SensorSample;

constexpr std::size_t kDoubles = 100;

void fill(Sample& sample, const std::string& robot, std::uint64_t seq) {
  sample.header().robot(robot);
  sample.header().seq(seq);
  sample.header().stamp_ns(static_cast<std::int64_t>(seq) * 1'000'000);
  sample.encoder_position().resize(kDoubles);
  for (std::size_t j = 0; j < kDoubles; ++j) {
    sample.encoder_position()[j] =
        std::sin(0.001 * static_cast<double>(seq) + static_cast<double>(j));
  }
}

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("wbi_bench_record_play_" + std::to_string(getpid()) + "_" + name);
}

// Records N topics fed by one writer thread; period 0: as fast as possible.
nlohmann::json record_run(std::size_t topics, double duration_s, std::chrono::nanoseconds period,
                          const char* profile) {
  wbi::dds::Participant publishers_side("bench publishers");
  wbi::dds::Participant recorder_side("bench recorder");
  std::vector<std::unique_ptr<wbi::dds::Publisher<Sample>>> publishers;
  for (std::size_t t = 0; t < topics; ++t) {
    publishers.push_back(std::make_unique<wbi::dds::Publisher<Sample>>(
        publishers_side, "wbi/bench" + std::to_string(t) + "/sensors", profile));
  }
  const auto file = scratch("record.mcap");
  wbi::recording::RecorderOptions options;
  options.output = file;
  wbi::recording::Recorder recorder(recorder_side, options);
  for (auto& publisher : publishers) {
    if (!publisher->wait_for_subscribers(1, std::chrono::seconds(10))) {
      throw std::runtime_error("the recorder did not subscribe within 10 s");
    }
  }
  // The writers see the recorder matched before the recorder's readers see the
  // writers; a volatile reader would drop what is written in between.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  Sample sample;
  std::uint64_t published = 0;
  std::uint64_t refused = 0;
  const auto start = Clock::now();
  const auto end = start + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(duration_s));
  auto next = start;
  for (std::uint64_t seq = 0; Clock::now() < end; ++seq) {
    for (std::size_t t = 0; t < topics; ++t) {
      fill(sample, "bench", seq);
      if (publishers[t]->publish(sample)) {
        ++published;
      } else {
        ++refused;
      }
    }
    if (period.count() > 0) {
      next += period;
      std::this_thread::sleep_until(next);
    }
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  for (auto& publisher : publishers) {
    publisher->wait_acknowledged(std::chrono::seconds(5));
  }
  const auto deadline = Clock::now() + std::chrono::seconds(5);  // the queue reaches the file
  while (recorder.progress().messages + recorder.progress().dropped < published &&
         Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  recorder.stop();
  const auto progress = recorder.progress();
  std::filesystem::remove(file);
  return {
      {"topics", topics},
      {"seconds", elapsed},
      {"published", published},
      {"refused_by_writer", refused},
      {"recorded", progress.messages},
      {"lost", published - std::min(published, progress.messages)},
      {"recorder_queue_drops", progress.dropped},
      {"queue_high_water", progress.queue_high_water},
      {"recorded_per_s", static_cast<double>(progress.messages) / elapsed},
      {"file_mib", static_cast<double>(progress.file_bytes) / (1024.0 * 1024.0)},
  };
}

nlohmann::json play_run(std::size_t count, int realtime_priority, std::chrono::nanoseconds spin,
                        double rate = 1.0) {
  const auto file = scratch("play.mcap");
  {
    wbi::mcap::Writer writer(file);
    const std::string type = "wbi::msg::SensorSample";
    const auto schema = writer.add_schema(type, wbi::msg::idl_text_for(type));
    const auto channel = writer.add_channel(schema, "wbi/bench_play/sensors", "cdr",
                                            {{"qos_profile", "wbi.stream"}});
    wbi::msg::SensorSamplePubSubType support;
    Sample sample;
    for (std::uint64_t seq = 0; seq < count; ++seq) {
      fill(sample, "bench_play", seq);
      eprosima::fastrtps::rtps::SerializedPayload_t payload(
          support.getSerializedSizeProvider(&sample)());
      support.serialize(&sample, &payload);
      writer.write(channel, static_cast<std::uint32_t>(seq), 1'000'000'000 + seq * 1'000'000,
                   seq * 1'000'000, {payload.data, payload.length});
    }
  }
  wbi::dds::Participant player_side("bench player");
  wbi::dds::Participant listener_side("bench listener");
  std::mutex mutex;
  std::vector<std::int64_t> arrivals;   // steady clock, at the listener
  std::vector<std::int64_t> published;  // DDS source timestamps: the player's write
  arrivals.reserve(count);
  published.reserve(count);
  wbi::dds::Subscriber<Sample> listener(
      listener_side, "wbi/bench_play/sensors", wbi::dds::qos::kStream,
      [&](const Sample&, const wbi::dds::detail::SampleInfo& info) {
        std::lock_guard lock(mutex);
        arrivals.push_back(info.received_ns);
        published.push_back(info.source_stamp_ns);
      });
  wbi::recording::PlayerOptions options;
  options.file = file;
  options.wait_for_subscribers = std::chrono::seconds(10);
  options.realtime_priority = realtime_priority;
  options.spin = spin;
  options.rate = rate;
  std::string warnings;
  options.log = [&warnings](const std::string& line) { warnings += line + "\n"; };
  wbi::recording::Player player(player_side, options);
  player.run();
  wbi::dds::Received<Sample> last;
  listener.wait_newer(last, count - 1, std::chrono::seconds(5));
  std::filesystem::remove(file);
  std::lock_guard lock(mutex);
  // Arrival intervals against 1 ms / rate: what a subscriber sees, its own wake-ups included.
  const double interval_us = 1000.0 / rate;
  std::vector<double> errors_us;
  for (std::size_t i = 2; i < arrivals.size(); ++i) {  // the first comes after the start-up wait
    errors_us.push_back(
        std::abs(1e-3 * static_cast<double>(arrivals[i] - arrivals[i - 1]) - interval_us));
  }
  // The same for the writes (their DDS source timestamps): the player's own
  // timing, without the delivery to the subscriber.
  std::vector<double> publish_errors_us;
  for (std::size_t i = 2; i < published.size(); ++i) {
    publish_errors_us.push_back(
        std::abs(1e-3 * static_cast<double>(published[i] - published[i - 1]) - interval_us));
  }
  if (errors_us.empty()) {
    throw std::runtime_error("the listener received nothing");
  }
  const double span_ratio = 1e-3 * static_cast<double>(arrivals.back() - arrivals[1]) /
                            (interval_us * static_cast<double>(arrivals.size() - 2));
  return {
      {"messages", count},
      {"received", arrivals.size()},
      {"rate", rate},
      {"span_ratio", span_ratio},
      {"interval_error_us_p50", percentile(errors_us, 0.50)},
      {"interval_error_us_p99", percentile(errors_us, 0.99)},
      {"interval_error_us_max", percentile(errors_us, 1.0)},
      {"publish_error_us_p50", percentile(publish_errors_us, 0.50)},
      {"publish_error_us_p99", percentile(publish_errors_us, 0.99)},
      {"publish_error_us_max", percentile(publish_errors_us, 1.0)},
      {"realtime_priority", realtime_priority},
      {"spin_us", 1e-3 * static_cast<double>(spin.count())},
      {"warnings", warnings},
  };
}

std::vector<std::size_t> parse_list(const std::string& text) {
  std::vector<std::size_t> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    values.push_back(static_cast<std::size_t>(std::stoul(item)));
  }
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  double duration_s = 3.0;
  std::vector<std::size_t> topic_counts{1, 10, 50};
  std::string json_file;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--duration" && i + 1 < argc) {
      duration_s = std::stod(argv[++i]);
    } else if (arg == "--topics" && i + 1 < argc) {
      topic_counts = parse_list(argv[++i]);
    } else if (arg == "--json" && i + 1 < argc) {
      json_file = argv[++i];
    } else {
      std::cerr << "usage: wbi_bench_record_play [--duration S] [--topics N,N,...] [--json FILE]\n";
      return 2;
    }
  }
  try {
    nlohmann::json result;
    for (const auto topics : topic_counts) {
      result["sustained_1khz"].push_back(
          record_run(topics, duration_s, std::chrono::milliseconds(1), wbi::dds::qos::kStream));
    }
    for (const auto topics : {std::size_t{1}, std::size_t{4}}) {
      result["max_rate"].push_back(
          record_run(topics, duration_s, std::chrono::nanoseconds(0), wbi::dds::qos::kCommand));
    }
    const auto play_count = static_cast<std::size_t>(duration_s * 1000);
    const wbi::recording::PlayerOptions defaults;
    result["play_1khz"] = play_run(play_count, 0, defaults.spin);
    // wbi play --realtime-priority 20, then also --spin-us 900
    result["play_1khz_realtime"] = play_run(play_count, 20, defaults.spin);
    result["play_1khz_realtime_spin900"] = play_run(play_count, 20, std::chrono::microseconds(900));
    // wbi play --rate 2: the same recording at twice its speed
    result["play_1khz_rate2"] = play_run(play_count, 0, defaults.spin, 2.0);
    const char* qos_file = std::getenv("WBI_QOS_FILE");
    result["qos_file"] = qos_file != nullptr ? qos_file : "";  // "": the built-in profiles
    std::cout << result.dump(2) << std::endl;
    if (!json_file.empty()) {
      std::ofstream(json_file) << result.dump(2) << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "wbi_bench_record_play: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
