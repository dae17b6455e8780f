// `wbi bag info`: what an MCAP recording holds (duration, size, compression,
// and per topic its type, message count and rate). The work is in wbi::mcap.
#include <algorithm>
#include <cstdint>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <wbi/mcap/reader.hpp>
#include <wbi/recording/recorded_events.hpp>

#include "../options.hpp"
#include "../subcommands.hpp"
#include "recording_file.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

constexpr double kNsPerSecond = 1e9;

// "1.2 MiB"
std::string human_size(std::uint64_t bytes) {
  static const char* const kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  double value = static_cast<double>(bytes);
  std::size_t unit = 0;
  while (value >= 1024.0 && unit + 1 < std::size(kUnits)) {
    value /= 1024.0;
    ++unit;
  }
  std::ostringstream out;
  out << std::fixed << std::setprecision(unit == 0 ? 0 : 1) << value << ' ' << kUnits[unit];
  return out.str();
}

// The compression of the chunks: "zstd", "lz4", "none", or "mixed" when they differ.
std::string compression_of(const mcap::FileInfo& info) {
  std::string found;
  for (const auto& chunk : info.chunks) {
    const std::string name = chunk.compression.empty() ? "none" : chunk.compression;
    if (found.empty()) {
      found = name;
    } else if (found != name) {
      return "mixed";
    }
  }
  return found.empty() ? "none" : found;
}

struct Topic {
  const mcap::Channel* channel;
  std::string type;  // the schema name, "" without schema
  std::string schema_encoding;
  std::uint64_t count;
  double rate_hz;  // count over the recording's duration
};

struct Summary {
  double duration_s = 0;
  std::uint64_t compressed_bytes = 0;
  std::uint64_t uncompressed_bytes = 0;
  std::vector<Topic> topics;
};

Summary summarise(const mcap::FileInfo& info) {
  Summary s;
  const auto& stats = info.statistics;
  if (stats.message_count > 0) {
    s.duration_s =
        static_cast<double>(stats.message_end_time - stats.message_start_time) / kNsPerSecond;
  }
  for (const auto& chunk : info.chunks) {
    s.compressed_bytes += chunk.compressed_size;
    s.uncompressed_bytes += chunk.uncompressed_size;
  }
  for (const auto& [id, channel] : info.channels) {
    Topic topic{&channel, "", "", 0, 0.0};
    if (const auto schema = info.schemas.find(channel.schema_id); schema != info.schemas.end()) {
      topic.type = schema->second.name;
      topic.schema_encoding = schema->second.encoding;
    }
    if (const auto count = stats.channel_message_counts.find(id);
        count != stats.channel_message_counts.end()) {
      topic.count = count->second;
    }
    topic.rate_hz = s.duration_s > 0 ? static_cast<double>(topic.count) / s.duration_s : 0.0;
    s.topics.push_back(topic);
  }
  return s;
}

// The events, one line each: when (the sender's stamp), severity, source, kind, text.
void print_events(const recording::RecordedEvents& recorded) {
  if (recorded.events.empty() && recorded.undecoded == 0) {
    return;
  }
  std::cout << "events:       " << recorded.events.size();
  if (recorded.undecoded > 0) {
    std::cout << "  (" << recorded.undecoded << " more did not decode)";
  }
  std::cout << "\n";
  std::size_t source_width = 6;
  for (const auto& event : recorded.events) {
    source_width = std::max(source_width, event.source.size());
  }
  for (const auto& event : recorded.events) {
    std::cout << "  "
              << utc_time(static_cast<std::uint64_t>(std::max<std::int64_t>(event.stamp_ns, 0)))
              << "  " << std::left << std::setw(7) << to_string(event.severity) << "  "
              << std::setw(static_cast<int>(source_width)) << event.source << "  " << std::setw(19)
              << to_string(event.kind) << std::right << "  " << event.text;
    if (!event.subject.empty()) {
      std::cout << "  [" << event.subject << "]";
    }
    if (event.suppressed > 0) {
      std::cout << "  (+" << event.suppressed << " suppressed)";
    }
    std::cout << "\n";
  }
}

nlohmann::ordered_json events_json(const recording::RecordedEvents& recorded) {
  auto events = nlohmann::ordered_json::array();
  for (const auto& event : recorded.events) {
    nlohmann::ordered_json entry;
    entry["stamp_ns"] = event.stamp_ns;
    entry["time"] = utc_time(static_cast<std::uint64_t>(std::max<std::int64_t>(event.stamp_ns, 0)));
    entry["log_time_ns"] = event.log_time;
    entry["severity"] = to_string(event.severity);
    entry["kind"] = to_string(event.kind);
    entry["robot"] = event.robot;
    entry["participant"] = event.participant;
    entry["source"] = event.source;
    entry["subject"] = event.subject;
    entry["text"] = event.text;
    entry["suppressed"] = event.suppressed;
    events.push_back(std::move(entry));
  }
  return events;
}

void print_json(const std::string& file, const mcap::FileInfo& info, const Summary& s,
                const recording::RecordedEvents& events) {
  const auto& stats = info.statistics;
  nlohmann::ordered_json out;
  out["path"] = file;
  out["size_bytes"] = info.file_size;
  out["profile"] = info.profile;
  out["library"] = info.library;
  out["messages"] = stats.message_count;
  out["duration_s"] = s.duration_s;
  out["start_ns"] = stats.message_start_time;
  out["end_ns"] = stats.message_end_time;
  out["start"] = stats.message_count > 0 ? utc_time(stats.message_start_time) : "";
  out["end"] = stats.message_count > 0 ? utc_time(stats.message_end_time) : "";
  out["compression"] = compression_of(info);
  out["chunks"] = info.chunks.size();
  out["compressed_bytes"] = s.compressed_bytes;
  out["uncompressed_bytes"] = s.uncompressed_bytes;
  out["attachments"] = stats.attachment_count;
  out["metadata"] = stats.metadata_count;
  out["from_summary"] = info.from_summary;
  out["truncated"] = info.truncated;
  if (info.truncated) {
    const auto& cut = info.truncation;
    nlohmann::ordered_json truncation;
    truncation["readable_bytes"] = cut.readable_bytes;
    truncation["cut_record"] = cut.cut_record;
    truncation["cut_record_offset"] = cut.cut_record_offset;
    truncation["cut_record_bytes"] = cut.cut_record_bytes;
    if (cut.lost_times_known) {
      truncation["lost_start_ns"] = cut.lost_start_time;
      truncation["lost_end_ns"] = cut.lost_end_time;
    }
    out["truncation"] = std::move(truncation);
  }
  out["warnings"] = info.warnings;
  auto topics = nlohmann::ordered_json::array();
  for (const auto& topic : s.topics) {
    nlohmann::ordered_json entry;
    entry["name"] = topic.channel->topic;
    entry["type"] = topic.type;
    entry["count"] = topic.count;
    entry["rate_hz"] = topic.rate_hz;
    entry["channel_id"] = topic.channel->id;
    entry["message_encoding"] = topic.channel->message_encoding;
    entry["schema_encoding"] = topic.schema_encoding;
    entry["metadata"] = topic.channel->metadata;
    topics.push_back(std::move(entry));
  }
  out["topics"] = std::move(topics);
  out["events"] = events_json(events);
  out["undecoded_events"] = events.undecoded;
  std::cout << out.dump(2) << "\n";
}

void print_text(const std::string& file, const mcap::FileInfo& info, const Summary& s) {
  const auto& stats = info.statistics;
  std::cout << "path:         " << file << "\n"
            << "size:         " << human_size(info.file_size) << " (" << info.file_size
            << " bytes)\n"
            << "profile:      " << (info.profile.empty() ? "(none)" : info.profile)
            << (info.library.empty() ? "" : "  (written by " + info.library + ")") << "\n"
            << "messages:     " << stats.message_count << "\n"
            << "duration:     " << std::fixed << std::setprecision(3) << s.duration_s << " s\n";
  if (stats.message_count > 0) {
    std::cout << "start:        " << utc_time(stats.message_start_time) << "  ("
              << stats.message_start_time << " ns)\n"
              << "end:          " << utc_time(stats.message_end_time) << "  ("
              << stats.message_end_time << " ns)\n";
  }
  std::cout << "compression:  " << compression_of(info) << "  (" << info.chunks.size() << " chunks";
  if (s.uncompressed_bytes > 0) {
    std::cout << ", " << human_size(s.uncompressed_bytes) << " -> "
              << human_size(s.compressed_bytes);
  }
  std::cout << ")\n";
  if (stats.attachment_count > 0 || stats.metadata_count > 0) {
    std::cout << "attachments:  " << stats.attachment_count
              << "    metadata: " << stats.metadata_count << "\n";
  }
  std::cout << "index:        " << (info.from_summary ? "summary" : "none (data section scanned)")
            << "\n"
            << "topics:       " << s.topics.size() << "\n";
  std::size_t name_width = 4;
  std::size_t type_width = 4;
  for (const auto& topic : s.topics) {
    name_width = std::max(name_width, topic.channel->topic.size());
    type_width = std::max(type_width, topic.type.size());
  }
  for (const auto& topic : s.topics) {
    std::cout << "  " << std::left << std::setw(static_cast<int>(name_width))
              << topic.channel->topic << "  " << std::setw(static_cast<int>(type_width))
              << (topic.type.empty() ? "-" : topic.type) << std::right << "  " << std::setw(10)
              << topic.count << " msgs  " << std::setw(10) << std::setprecision(1) << topic.rate_hz
              << " Hz  " << topic.channel->message_encoding << "\n";
  }
}

constexpr const char* kInfoExample = "wbi bag info run.mcap";

int run_info(Args args) {
  Options options("wbi bag info FILE [options]",
                  "Prints what an MCAP recording holds: its duration, start and end, size and\n"
                  "compression, and per topic its type, message count and rate; then the events\n"
                  "of wbi/events it holds (time, severity, source, kind, text). Uses the file's\n"
                  "summary when it has one, else scans it (the events: a pass over the file). A\n"
                  "truncated file (e.g. a killed recorder) prints what could be read, then one\n"
                  "line saying where it ends and what was lost, and exits 1; an empty, foreign\n"
                  "or corrupt file is a one-line error (exit 1).");
  options.positional("FILE", "the .mcap file");
  options.flag("json", "print one JSON object instead of text");
  options.flag("verify", "also read every chunk and check every CRC (reads the whole file)");
  options.example(kInfoExample, "topics, types, counts, rates and events of a wbi record file");
  options.example("wbi bag info run.mcap --verify --json", "every CRC checked, as JSON");
  if (!options.parse(args)) {
    return kExitOk;
  }
  const std::string file = options.get("FILE");
  const mcap::Reader reader(file);
  if (options.has("verify")) {
    reader.verify();
  }
  const auto& info = reader.info();
  require_readable_recording(file, info);  // else nothing to summarise: one line
  for (const auto& warning : info.warnings) {
    if (!info.truncated || warning != info.truncation.description) {
      std::cerr << "wbi bag: warning: " << file << ": " << warning << "\n";
    }
  }
  const Summary summary = summarise(info);
  const auto events = recording::read_events(reader);
  if (options.has("json")) {
    print_json(file, info, summary, events);
  } else {
    print_text(file, info, summary);
    print_events(events);
  }
  if (info.truncated) {
    std::cout.flush();
    std::cerr << "wbi bag: " << truncation_line(file, info) << "\n";
    return kExitError;
  }
  return kExitOk;
}

}  // namespace

int run_bag_compare(Args args);  // bag_compare.cpp
extern const char* const kBagCompareExample;

int run_bag(Args args) {
  return run_subcommand(
      "bag", args,
      {
          {"info", "print what an MCAP recording holds", kInfoExample, run_info},
          {"compare", "whether two recordings hold the same messages (first difference)",
           kBagCompareExample, run_bag_compare},
      });
}

}  // namespace wbi::cli
