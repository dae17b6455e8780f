// `wbi record`: records DDS topics to an MCAP file. The work is in
// wbi::recording::Recorder (tools/recording); this file parses the
// command line, shows progress and stops on Ctrl-C, SIGTERM or --duration.
#include <atomic>
#include <chrono>
#include <csignal>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <wbi/recording/recorder.hpp>

#include "../join_options.hpp"
#include "../options.hpp"
#include "../terminal.hpp"
#include "record_window.hpp"
#include "recorder_participant.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_record_signal(int /*signal*/) { stop_requested = true; }

mcap::Compression compression_named(const std::string& name) {
  if (name == "none") {
    return mcap::Compression::none;
  }
  if (name == "zstd") {
    return mcap::Compression::zstd;
  }
  if (name == "lz4") {
    return mcap::Compression::lz4;
  }
  throw UsageError("--compression must be none, zstd or lz4, got '" + name + "'");
}

std::string progress_text(const recording::RecorderProgress& now,
                          const recording::RecorderProgress& before, double elapsed_s,
                          double window_s) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << "recording " << elapsed_s << " s  messages "
      << now.messages << "  " << human_bytes(static_cast<double>(now.file_bytes)) << "  rate "
      << static_cast<double>(now.messages - before.messages) / window_s << " msg/s  topics "
      << now.topics;
  if (now.dropped > 0) {
    out << "  DROPPED " << now.dropped;
  }
  if (now.lost > 0) {
    out << "  LOST " << now.lost;
  }
  if (now.foreign > 0) {
    out << "  FOREIGN " << now.foreign;
  }
  return out.str();
}

}  // namespace

int run_record(Args args) {
  Options options(
      "wbi record -o FILE.mcap [TOPIC_REGEX...] [--all] [options]\n"
      "       wbi record --window BEFORE:AFTER --trigger KIND[,KIND...] -o DIRECTORY\n"
      "                  [TOPIC_REGEX...] [--all] [options]",
      "Records DDS topics to an MCAP file until Ctrl-C (or SIGTERM, or --duration).\n"
      "Topics are found through discovery, also those that appear later; a topic is\n"
      "recorded when its name fully matches a TOPIC_REGEX (ECMAScript), or with --all.\n"
      "Log time: when a sample was received (system time); publish time: its\n"
      "Header.stamp_ns, or the log time for types without a Header. The file is\n"
      "flushed every 0.5 s: a killed recorder leaves it readable up to then.\n"
      "Prints a progress line once a second (in place on a terminal) and a summary.\n"
      "Exit: 0 when stopped by Ctrl-C, SIGTERM or --duration (the file is complete).\n"
      "\n"
      "With --window, the topics are kept in memory (the last BEFORE s, within\n"
      "--max-memory, printed at the start) and wbi/events is watched: an event of a\n"
      "--trigger kind writes BEFORE s before it and AFTER s after it (events included)\n"
      "to DIRECTORY/<UTC time>_<KIND>.mcap; a trigger while that file is open extends\n"
      "it. A window the memory cannot hold at the rate seen in the first --probe s is\n"
      "refused (exit 1).");
  options.rest("TOPIC_REGEX", "record the topics whose names fully match one of these");
  options.option("output", "FILE",
                 "the MCAP file to write (also -o FILE); with --window, the directory");
  options.flag("all", "record every topic");
  options.option("exclude", "REGEX", "do not record topics whose names fully match this");
  options.option("duration", "SECONDS", "stop after this long (0: until Ctrl-C)", "0");
  options.option("split-size", "MB",
                 "start a new file past this size; files are STEM_0.mcap, STEM_1.mcap, ...");
  options.option("compression", "KIND", "chunk compression: none, zstd or lz4", "zstd");
  options.option("queue", "N", "samples that may wait for the writer thread before drops", "16384");
  add_window_options(options);
  add_join_options(options, true, "observer");
  options.example("wbi record -o run.mcap --all --duration 10",
                  "every topic for 10 s (e.g. of wbi launch deploy/demo.yaml)");
  options.example("wbi record -o arm.mcap 'wbi/arm/.*' --exclude 'wbi/arm/commands'",
                  "the arm's topics but its commands, until Ctrl-C");
  options.example("wbi record --window 10:2 --trigger WATCHDOG_TRIP,PROCESS_EXITED -o faults --all",
                  "10 s before and 2 s after each fault, one file each in faults/");
  if (!options.parse(args)) {
    return kExitOk;
  }
  if (options.has("all")) {
    if (!options.rest_values().empty()) {
      throw UsageError("give TOPIC_REGEX arguments or --all, not both");
    }
  } else if (options.rest_values().empty()) {
    throw UsageError("give TOPIC_REGEX arguments or --all");
  }
  if (options.has("window")) {
    if (options.has("split-size")) {
      throw UsageError("--split-size does not go with --window (each window is one file)");
    }
    std::signal(SIGINT, on_record_signal);
    std::signal(SIGTERM, on_record_signal);
    return run_window_record(options, compression_named(options.get("compression")),
                             stop_requested);
  }
  if (const auto name = window_only_option_given(options); !name.empty()) {
    throw UsageError("--" + name + " goes with --window");
  }
  recording::RecorderOptions recorder_options;
  if (!options.has("output")) {
    throw UsageError("missing -o FILE.mcap");
  }
  recorder_options.output = options.get("output");
  recorder_options.topic_patterns = options.rest_values();
  recorder_options.exclude_pattern = options.get_optional("exclude").value_or("");
  const double duration_s = options.get_double("duration");
  if (duration_s < 0) {
    throw UsageError("--duration must be >= 0");
  }
  if (options.has("split-size")) {
    const double megabytes = options.get_double("split-size");
    if (!(megabytes > 0)) {
      throw UsageError("--split-size must be > 0 MB");
    }
    recorder_options.split_size_bytes = static_cast<std::uint64_t>(megabytes * 1024 * 1024);
  }
  recorder_options.compression = compression_named(options.get("compression"));
  const long queue = options.get_int("queue");
  if (queue <= 0) {
    throw UsageError("--queue must be > 0");
  }
  recorder_options.queue_capacity = static_cast<std::size_t>(queue);
  recorder_options.log = [](const std::string& line) { std::cerr << line << std::endl; };

  // On a secured deployment the recorder joins as the observer (subscribe only).
  const dds::ParticipantOptions participant_options = recorder_participant_options(options);
  std::signal(SIGINT, on_record_signal);
  std::signal(SIGTERM, on_record_signal);
  dds::Participant participant(participant_options);
  recording::Recorder recorder(participant, recorder_options);
  std::cerr << "recording to " << recorder.files().front().string() << " (Ctrl-C to stop)"
            << std::endl;

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_report = start;
  recording::RecorderProgress reported;
  ProgressLine line;
  while (!stop_requested && !recorder.progress().failed) {
    const auto now = clock::now();
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (duration_s > 0 && elapsed >= duration_s) {
      break;
    }
    if (now - last_report >= std::chrono::seconds(1)) {
      const auto progress = recorder.progress();
      line.show(progress_text(progress, reported, elapsed,
                              std::chrono::duration<double>(now - last_report).count()));
      reported = progress;
      last_report = now;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(
        20));  // polls the signal flag and the clock; the work is on the recorder's thread
  }
  recorder.stop();  // throws the writer thread's error, if any
  line.finish();
  const auto done = recorder.progress();
  std::cout << "recorded " << done.messages << " messages on " << done.topics << " topics, "
            << human_bytes(static_cast<double>(done.file_bytes)) << " in " << done.files
            << (done.files == 1 ? " file" : " files") << ", dropped " << done.dropped
            << ", lost before the recorder " << done.lost << std::endl;
  warn_if_lost(recorder.losses());
  if (done.dropped > 0) {
    std::cerr << "warning: " << done.dropped
              << " samples were dropped (the writer could not keep up; try --queue or "
                 "--compression none)"
              << std::endl;
  }
  if (done.foreign > 0) {
    std::cerr << "warning: " << done.foreign
              << " samples of a second writer of a robot stream were not recorded (two robots "
                 "of one name on this domain? each robot stream is recorded from one writer)"
              << std::endl;
  }
  return kExitOk;
}

}  // namespace wbi::cli
