// The windowed mode of `wbi record`: the work is in
// wbi::recording::WindowRecorder (tools/recording); this file reads the
// options, checks the window against the memory bound once the topics' rate
// has been seen, and shows progress.
#include "record_window.hpp"

#include <cctype>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>

#include <wbi/recording/window_recorder.hpp>

#include "../join_options.hpp"
#include "../terminal.hpp"
#include "recorder_participant.hpp"

namespace wbi::cli {

namespace {

constexpr const char* kWindowOnly[] = {"trigger", "max-files", "max-memory", "probe"};

// "256M", "256MiB", "1.5G", "1048576" (bytes); K, M, G are powers of 1024.
std::size_t parse_size(const std::string& text) {
  std::size_t digits = 0;
  while (digits < text.size() &&
         (std::isdigit(static_cast<unsigned char>(text[digits])) != 0 || text[digits] == '.')) {
    ++digits;
  }
  std::string unit = text.substr(digits);
  if (unit.size() == 3 && (unit.substr(1) == "iB" || unit.substr(1) == "ib")) {
    unit = unit.substr(0, 1);
  }
  double scale = 0;
  if (unit.empty() || unit == "B") {
    scale = 1;
  } else if (unit == "K" || unit == "k") {
    scale = 1024.0;
  } else if (unit == "M" || unit == "m") {
    scale = 1024.0 * 1024.0;
  } else if (unit == "G" || unit == "g") {
    scale = 1024.0 * 1024.0 * 1024.0;
  }
  double value = -1;
  try {
    std::size_t used = 0;
    value = digits == 0 ? -1 : std::stod(text.substr(0, digits), &used);
    value = used == digits ? value : -1;
  } catch (const std::exception&) {
    value = -1;
  }
  if (scale == 0 || !(value > 0) || !std::isfinite(value * scale)) {
    throw UsageError("--max-memory '" + text + "': not a size (e.g. 256M, 1G, 64MiB)");
  }
  return static_cast<std::size_t>(value * scale);
}

std::string seconds(double s) {
  std::ostringstream out;
  out << std::setprecision(3) << s << " s";
  return out.str();
}

std::string kinds_text(const std::vector<EventKind>& kinds) {
  std::string text;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    text +=
        (i == 0 ? "" : (i + 1 == kinds.size() ? " or " : ", ")) + std::string(to_string(kinds[i]));
  }
  return text;
}

std::string progress_text(const recording::WindowProgress& now,
                          const recording::WindowMemory& memory, double elapsed_s) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << "watching " << elapsed_s << " s  ring "
      << human_bytes(static_cast<double>(now.ring_used_bytes)) << " of "
      << human_bytes(static_cast<double>(memory.ring_bytes)) << " (" << now.ring_span_s
      << " s)  topics " << now.topics << "  events " << now.events << "  triggers " << now.triggers
      << "  files " << now.files_written << (now.file_open ? " +1 open" : "");
  if (now.evicted_in_window > 0) {
    out << "  EVICTED-IN-WINDOW " << now.evicted_in_window;
  }
  if (now.lost_to_file > 0) {
    out << "  LOST " << now.lost_to_file;
  }
  return out.str();
}

// Refuses a window the ring cannot hold at the rate seen so far.
void check_window_fits(const recording::WindowRecorder& recorder,
                       const recording::WindowRecorderOptions& window, const std::string& text,
                       double observed_s) {
  const auto now = recorder.progress();
  const double rate = static_cast<double>(now.received_bytes) / observed_s;
  const auto& memory = recorder.memory();
  const std::uint64_t needed = recording::window_bytes_needed(rate, window.before);
  const double held_s = rate > 0 ? static_cast<double>(memory.ring_bytes) / rate
                                 : std::numeric_limits<double>::infinity();
  if (needed > memory.ring_bytes) {
    throw std::runtime_error(
        "--window " + text + " needs " +
        human_bytes(static_cast<double>(needed + memory.batch_bytes + memory.writer_bytes)) +
        " of memory (" +
        seconds(std::chrono::duration<double>(window.before + recording::kTriggerSlack).count()) +
        " of the " + human_bytes(rate) + "/s seen over " + seconds(observed_s) + " on " +
        std::to_string(now.topics) + " topics, plus " +
        human_bytes(static_cast<double>(memory.batch_bytes + memory.writer_bytes)) +
        " for writing), more than --max-memory " +
        human_bytes(static_cast<double>(memory.total())) + ": raise it or shorten BEFORE");
  }
  if (rate > 0) {
    std::cerr << "window: " << human_bytes(rate) << "/s seen over " << seconds(observed_s) << " on "
              << now.topics << " topics: the ring holds " << seconds(held_s) << " of it"
              << std::endl;
  } else {
    std::cerr << "window: no samples in the first " << seconds(observed_s)
              << "; the ring holds the window up to "
              << human_bytes(static_cast<double>(memory.ring_bytes) /
                             std::chrono::duration<double>(window.before + recording::kTriggerSlack)
                                 .count())
              << "/s" << std::endl;
  }
}

}  // namespace

void add_window_options(Options& options) {
  options.option("window", "BEFORE:AFTER",
                 "keep BEFORE s in memory; on a trigger event write BEFORE s before it and AFTER s "
                 "after it to a file in the -o directory");
  options.option(
      "trigger", "KIND[,KIND...]",
      "event kinds that write a window (wbi/events: WATCHDOG_TRIP, PROCESS_EXITED, ...)");
  options.option("max-files", "N",
                 "windowed: keep at most N files, deleting the oldest (default 0: no limit)");
  options.option("max-memory", "SIZE", "windowed: the memory bound (e.g. 64M, 1G; default 256M)");
  options.option("probe", "SECONDS",
                 "windowed: watch the topics' rate this long, then refuse a window the memory "
                 "cannot hold (default 1)");
}

std::string window_only_option_given(const Options& options) {
  for (const char* name : kWindowOnly) {
    if (options.has(name)) {
      return name;
    }
  }
  return "";
}

int run_window_record(const Options& options, mcap::Compression compression,
                      const std::atomic<bool>& stop) {
  recording::WindowRecorderOptions window;
  window.compression = compression;
  const std::string window_text = options.get("window");
  try {
    const auto span = recording::parse_window(window_text);
    window.before = span.before;
    window.after = span.after;
    if (!options.has("trigger")) {
      throw UsageError("--window needs --trigger KIND[,KIND...]");
    }
    window.triggers = recording::parse_trigger_kinds(options.get("trigger"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (!options.has("output")) {
    throw UsageError("missing -o DIRECTORY (the windows' files go there)");
  }
  window.directory = options.get("output");
  window.topic_patterns = options.rest_values();
  window.exclude_pattern = options.get_optional("exclude").value_or("");
  window.max_memory_bytes = parse_size(options.get_optional("max-memory").value_or("256M"));
  const long max_files = options.has("max-files") ? options.get_int("max-files") : 0;
  if (max_files < 0) {
    throw UsageError("--max-files must be >= 0");
  }
  window.max_files = static_cast<std::size_t>(max_files);
  const double probe_s = options.has("probe") ? options.get_double("probe") : 1.0;
  const double duration_s = options.get_double("duration");
  if (!(probe_s >= 0) || !(duration_s >= 0)) {
    throw UsageError("--probe and --duration must be >= 0");
  }
  window.log = [](const std::string& line) { std::cerr << line << std::endl; };
  const auto memory = [&] {
    try {
      return recording::window_memory(window.max_memory_bytes);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }();

  dds::Participant participant(recorder_participant_options(options));
  recording::WindowRecorder recorder(participant, window);
  std::cerr << "window: " << seconds(std::chrono::duration<double>(window.before).count())
            << " before and " << seconds(std::chrono::duration<double>(window.after).count())
            << " after each " << kinds_text(window.triggers) << " event, files in "
            << window.directory.string();
  if (window.max_files > 0) {
    std::cerr << " (at most " << window.max_files << ", the oldest deleted)";
  }
  std::cerr << "\nwindow: memory bound " << human_bytes(static_cast<double>(memory.total())) << " ("
            << memory.total() << " bytes: ring "
            << human_bytes(static_cast<double>(memory.ring_bytes)) << ", writing "
            << human_bytes(static_cast<double>(memory.batch_bytes + memory.writer_bytes)) << ")"
            << std::endl;

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
  bool probed = probe_s == 0;
  auto last_report = start;
  std::uint64_t warned_evictions = 0;
  ProgressLine line;
  while (!stop && !recorder.progress().failed && !(duration_s > 0 && elapsed() >= duration_s)) {
    std::this_thread::sleep_for(
        std::chrono::milliseconds(20));  // polls the flags; the work is on the recorder's threads
    if (!probed && elapsed() >= probe_s) {
      probed = true;
      check_window_fits(recorder, window, window_text, elapsed());
    }
    if (clock::now() - last_report >= std::chrono::seconds(1)) {
      last_report = clock::now();
      const auto now = recorder.progress();
      line.show(progress_text(now, memory, elapsed()));
      if (now.evicted_in_window > warned_evictions) {
        line.finish();
        std::cerr << "warning: the ring holds only " << seconds(now.ring_span_s) << " ("
                  << seconds(std::chrono::duration<double>(window.before + recording::kTriggerSlack)
                                 .count())
                  << " needed): windows will be shorter; raise --max-memory or record fewer topics"
                  << std::endl;
        warned_evictions = now.evicted_in_window;
      }
    }
  }
  recorder.stop();  // throws the writer thread's error, if any
  line.finish();
  const auto done = recorder.progress();
  std::cout << "window recorder: " << done.triggers << " triggers (" << done.triggers_merged
            << " merged into an open file, " << done.triggers_before_start
            << " from before the start ignored), " << done.files_written << " files written, "
            << done.files_deleted << " deleted; " << done.received << " samples on " << done.topics
            << " topics, evicted inside the window " << done.evicted_in_window
            << ", lost to a file " << done.lost_to_file << ", too large " << done.too_large
            << ", lost before the recorder " << done.lost << std::endl;
  warn_if_lost(recorder.losses());
  return kExitOk;
}

}  // namespace wbi::cli
