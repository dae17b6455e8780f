// What a windowed recorder's file holds, for the tests: the trigger events
// in it (wbi/events), how far a stream reaches before the first and after the
// last of them, and the gaps in that stream's Header.seq. Stream "*": every
// topic whose type starts with a Header and that has one writer (channel
// metadata "writers" when the recorder found it; wbi/status is every
// component's, their sequences interleave), the events aside, each counted on
// its own sequence.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <wbi/dds/cdr.hpp>
#include <wbi/mcap/reader.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "source_stamp.hpp"

namespace wbi::test {

// One sample of the stream: its Header.seq and the time the recorder logged it.
struct StreamSample {
  std::uint64_t seq = 0;
  std::uint64_t log_time = 0;
};

struct WindowFileReport {
  std::size_t events = 0;
  std::vector<std::string> trigger_sources;  // one per trigger event, in log-time order
  std::int64_t first_trigger_ns = 0;         // their stamps
  std::int64_t last_trigger_ns = 0;
  std::vector<StreamSample> stream;  // in log-time order ("*": every such topic's, interleaved)
  double before_s = 0;               // first trigger − first sample of the stream (log times)
  double after_s = 0;                // last sample of the stream − last trigger
  // Header.seq steps other than +1 within one writer's run (a step back is a
  // new incarnation, not a gap), and the samples they skip.
  std::size_t gaps = 0;
  std::uint64_t missing = 0;
  std::map<std::string, std::uint64_t> missing_by_topic;  // the topics with gaps
  std::string problem;  // empty: the file could be read and decoded
};

// The first trigger's stamp, to the millisecond, from a window file's name
// (window_file_name: "20261127-235513.123_KIND.mcap"); 0 when it is not one.
inline std::int64_t window_file_time_ns(const std::filesystem::path& file) {
  std::tm utc{};
  int millis = 0;
  const std::string name = file.filename().string();
  if (std::sscanf(name.c_str(), "%4d%2d%2d-%2d%2d%2d.%3d_", &utc.tm_year, &utc.tm_mon, &utc.tm_mday,
                  &utc.tm_hour, &utc.tm_min, &utc.tm_sec, &millis) != 7) {
    return 0;
  }
  utc.tm_year -= 1900;
  utc.tm_mon -= 1;
  return static_cast<std::int64_t>(timegm(&utc)) * 1'000'000'000 + millis * 1'000'000LL;
}

// stream: a SensorSample topic (e.g. wbi/arm/sensors); triggers: the kinds
// the recorder was started with. The file's triggers are those stamped at or
// after the time in its name: its BEFORE may reach back over an earlier
// fault's events.
inline WindowFileReport check_window_file(const std::filesystem::path& file,
                                          const std::string& stream,
                                          const std::vector<wbi::EventKind>& triggers) {
  const std::int64_t first_trigger_floor = window_file_time_ns(file);
  WindowFileReport report;
  std::map<std::string, std::uint64_t> previous_seq;  // per topic
  std::map<std::string, bool> has_header;
  const bool every_topic = stream == "*";
  try {
    const mcap::Reader reader(file);
    auto cursor = reader.messages(mcap::Order::log_time);
    while (const auto* message = cursor.next()) {
      const std::string& topic = message->channel->topic;
      if (topic == "wbi/events") {
        msg::Event event;
        if (!dds::decode_cdr(message->data, event)) {
          report.problem = "an event does not decode";
          return report;
        }
        ++report.events;
        const auto kind = msg::from_wire(event.kind());
        const std::int64_t stamp = event.header().stamp_ns();
        if (kind && std::find(triggers.begin(), triggers.end(), *kind) != triggers.end() &&
            stamp >= first_trigger_floor) {
          report.first_trigger_ns =
              report.trigger_sources.empty() ? stamp : std::min(report.first_trigger_ns, stamp);
          report.last_trigger_ns = std::max(report.last_trigger_ns, stamp);
          report.trigger_sources.push_back(event.source().to_string());
        }
      } else if (topic == stream || every_topic) {
        std::optional<std::uint64_t> seq;
        if (every_topic) {
          auto known = has_header.find(topic);
          if (known == has_header.end()) {
            const auto writers = message->channel->metadata.find("writers");
            known = has_header
                        .emplace(topic, message->schema != nullptr && topic != "wbi/status" &&
                                            writers != message->channel->metadata.end() &&
                                            writers->second == "1" &&
                                            recording::starts_with_header(
                                                message->schema->name,
                                                std::string(message->schema->data.begin(),
                                                            message->schema->data.end())))
                        .first;
          }
          if (!known->second) {
            continue;
          }
          seq = recording::header_seq(message->data);
        } else {
          msg::SensorSample sample;
          if (dds::decode_cdr(message->data, sample)) {
            seq = sample.header().seq();
          }
        }
        if (!seq) {
          report.problem = "a sample of " + topic + " does not decode";
          return report;
        }
        const auto previous = previous_seq.find(topic);
        if (previous != previous_seq.end() && *seq > previous->second + 1) {
          ++report.gaps;
          report.missing += *seq - previous->second - 1;
          report.missing_by_topic[topic] += *seq - previous->second - 1;
        }
        previous_seq[topic] = *seq;
        report.stream.push_back({*seq, message->log_time});
      }
    }
  } catch (const std::exception& e) {
    report.problem = e.what();
    return report;
  }
  if (report.trigger_sources.empty()) {
    report.problem = "no trigger event in the file";
  } else if (report.stream.empty()) {
    report.problem = "no sample of " + stream + " in the file";
  } else {
    const auto first = static_cast<std::int64_t>(report.stream.front().log_time);
    const auto last = static_cast<std::int64_t>(report.stream.back().log_time);
    report.before_s = 1e-9 * static_cast<double>(report.first_trigger_ns - first);
    report.after_s = 1e-9 * static_cast<double>(last - report.last_trigger_ns);
  }
  return report;
}

// The log time of the stream's sample `seq` in a file, if the file holds it
// (a named stream: under "*" the topics' sequences overlap).
inline std::optional<std::uint64_t> log_time_of(const WindowFileReport& report, std::uint64_t seq) {
  for (const auto& sample : report.stream) {
    if (sample.seq == seq) {
      return sample.log_time;
    }
  }
  return std::nullopt;
}

}  // namespace wbi::test
