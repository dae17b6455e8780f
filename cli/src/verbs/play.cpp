// `wbi play`: replays an MCAP recording onto DDS. The work is in
// wbi::recording::Player (tools/recording); this file parses the command
// line, shows progress and takes pause/resume/step from the keyboard and from
// the control topic.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <wbi/dds/subscriber.hpp>
#include <wbi/recording/player.hpp>

#include "../join_options.hpp"
#include "../options.hpp"
#include "../terminal.hpp"
#include "recording_file.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

std::atomic<bool> interrupted{false};
extern "C" void on_play_signal(int /*signal*/) { interrupted = true; }

constexpr const char* kControlTopic = "wbi/play/control";

// Takes every --remap FROM:=TO out of args (the option may repeat).
std::map<std::string, std::string> take_remaps(std::vector<std::string>& args) {
  std::map<std::string, std::string> remaps;
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string value;
    if (args[i] == "--remap") {
      if (i + 1 >= args.size()) {
        throw UsageError("option --remap needs a value FROM:=TO");
      }
      value = args[++i];
    } else if (args[i].rfind("--remap=", 0) == 0) {
      value = args[i].substr(8);
    } else {
      rest.push_back(args[i]);
      continue;
    }
    const auto separator = value.find(":=");
    if (separator == std::string::npos || separator == 0 || separator + 2 == value.size()) {
      throw UsageError("--remap expects FROM:=TO, got '" + value + "'");
    }
    remaps[value.substr(0, separator)] = value.substr(separator + 2);
  }
  args = std::move(rest);
  return remaps;
}

void apply_command(recording::Player& player, msg::PlaybackAction action) {
  switch (action) {
    case msg::PAUSE:
      player.pause();
      return;
    case msg::RESUME:
      player.resume();
      return;
    case msg::TOGGLE_PAUSE:
      player.toggle_pause();
      return;
    case msg::STEP:
      player.step();
      return;
    case msg::QUIT:
      player.quit();
      return;
  }
  std::cerr << "wbi play: unknown playback action " << static_cast<int>(action) << " on "
            << kControlTopic << std::endl;
}

std::string progress_text(const recording::PlayerProgress& progress) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << (progress.paused ? "paused  " : "playing ")
      << progress.position_s << " / " << progress.duration_s << " s  messages "
      << progress.published;
  if (progress.refused > 0) {
    out << "  refused " << progress.refused;
  }
  if (progress.clock_ticks > 0) {
    out << "  clock ticks " << progress.clock_ticks;
  }
  if (progress.loops > 0) {
    out << "  loops " << progress.loops;
  }
  return out.str();
}

}  // namespace

int run_play(Args raw_args) {
  Options options(
      "wbi play FILE [options]",
      "Replays an MCAP recording onto DDS: each topic with its recorded type (the\n"
      "schema name) and QoS (the channel metadata), messages in log-time order at\n"
      "their recorded spacing divided by --rate.\n"
      "Keys on a terminal: space pause/resume, s step (while paused), q quit.\n"
      "Control topic wbi/play/control (type wbi::msg::PlaybackCommand, idl/playback.idl:\n"
      "PAUSE, RESUME, TOGGLE_PAUSE, STEP, QUIT) does the same from a program.\n"
      "Prints a progress line once a second. Exit: 0 at the end, 130 on Ctrl-C.");
  options.positional("FILE", "the MCAP recording");
  options.option("rate", "R", "speed factor: 2 plays twice as fast", "1");
  options.flag("loop", "start over at the end, until Ctrl-C or q");
  options.option("start-offset", "SECONDS", "skip the first seconds of the recording", "0");
  options.option("topics", "REGEX", "play only topics whose names fully match this");
  options.option("remap", "FROM:=TO", "publish topic FROM as TO (may repeat)");
  options.flag("clock", "publish the recording's time as SimulationClock on wbi/clock");
  options.option("clock-rate", "HZ", "SimulationClock samples per recorded second", "100");
  options.option("wait-subscribers", "SECONDS",
                 "first wait up to this long for a subscriber on every topic (0: start at once)",
                 "0");
  options.flag("paused", "start paused (space or 'resume' on the control topic to start)");
  options.option("spin-us", "US",
                 "spin, not sleep, this long before each message: timing for CPU (max 1000000)",
                 "200");
  options.option("realtime-priority", "N",
                 "play at SCHED_FIFO priority N (1-99), on time under load (needs "
                 "CAP_SYS_NICE; else a warning; 0: off)",
                 "0");
  add_join_options(options);
  options.example("wbi play run.mcap", "a recording of wbi record, at its recorded pace");
  options.example("wbi play run.mcap --rate 0.5 --loop", "at half speed, over and over");
  options.example("wbi play run.mcap --topics 'wbi/arm/state' --clock",
                  "the arm's state alone, with the recording's time on wbi/clock");
  std::vector<std::string> args(raw_args.begin(), raw_args.end());
  const bool wants_help = std::find(args.begin(), args.end(), "--help") != args.end() ||
                          std::find(args.begin(), args.end(), "-h") != args.end();
  recording::PlayerOptions player_options;
  if (!wants_help) {
    player_options.remap = take_remaps(args);
  }
  if (!options.parse(args)) {
    return kExitOk;
  }
  player_options.file = options.get("FILE");
  player_options.rate = options.get_double("rate");
  player_options.loop = options.has("loop");
  player_options.start_offset_s = options.get_double("start-offset");
  player_options.topics_pattern = options.get_optional("topics").value_or("");
  player_options.clock = options.has("clock");
  player_options.clock_rate_hz = options.get_double("clock-rate");
  // The player checks the range; the clamp only keeps a huge value from wrapping to a valid one.
  player_options.realtime_priority = static_cast<int>(
      std::clamp<long>(options.get_int("realtime-priority"), std::numeric_limits<int>::min(),
                       std::numeric_limits<int>::max()));
  const long spin_us = options.get_int("spin-us");
  if (spin_us < 0 || spin_us > 1'000'000) {
    throw UsageError("--spin-us must be in [0, 1000000], got " + std::to_string(spin_us));
  }
  player_options.spin = std::chrono::microseconds(spin_us);
  const double wait_s = options.get_double("wait-subscribers");
  if (wait_s < 0) {
    throw UsageError("--wait-subscribers must be >= 0");
  }
  player_options.wait_for_subscribers =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(wait_s));
  player_options.log = [](const std::string& line) { std::cerr << line << std::endl; };
  if (!std::filesystem::exists(player_options.file)) {
    throw std::runtime_error(player_options.file.string() + ": no such file");
  }
  // Not a recording: one line, before anything joins the domain. A truncated
  // one plays what is readable, then says what was lost (exit 1).
  const mcap::FileInfo file_info = mcap::Reader(player_options.file.string()).info();
  require_readable_recording(player_options.file.string(), file_info);

  // No default identity: on a secured deployment, play publishes, so the
  // user names an identity allowed to publish what it replays.
  const dds::ParticipantOptions participant_options = join_options(options, "wbi play", "");
  dds::Participant participant(participant_options);
  std::optional<recording::Player> made;
  try {
    made.emplace(participant, player_options);
  } catch (const std::runtime_error& error) {
    if (!participant_options.security.enabled()) {
      throw;
    }
    // Access control refuses a writer the identity's permissions do not grant.
    throw std::runtime_error("identity '" + participant_options.security.identity +
                             "' may not publish what this recording holds (" + error.what() +
                             "): give --identity NAME of an identity allowed to publish it");
  }
  recording::Player& player = *made;
  if (options.has("paused")) {
    player.pause();
  }
  for (const auto& [topic, type] : player.topics()) {
    std::cerr << "playing " << topic << " [" << type << "]" << std::endl;
  }
  dds::Subscriber<msg::PlaybackCommand> control(
      participant, kControlTopic, dds::qos::kCommand,
      [&player](const msg::PlaybackCommand& command, const dds::detail::SampleInfo&) {
        apply_command(player, command.action());
      });

  std::signal(SIGINT, on_play_signal);
  std::signal(SIGTERM, on_play_signal);
  std::atomic<bool> finished{false};
  std::exception_ptr failure;
  std::thread playing([&] {
    try {
      player.run();
    } catch (...) {
      failure = std::current_exception();
    }
    finished = true;
  });
  Keyboard keyboard;
  ProgressLine line;
  auto last_report = std::chrono::steady_clock::now();
  while (!finished) {
    if (interrupted) {
      player.quit();
    }
    if (const auto key = keyboard.poll(std::chrono::milliseconds(20))) {
      if (*key == ' ') {
        player.toggle_pause();
      } else if (*key == 's') {
        player.step();
      } else if (*key == 'q') {
        player.quit();
      }
    }
    if (std::chrono::steady_clock::now() - last_report >= std::chrono::seconds(1)) {
      line.show(progress_text(player.progress()));
      last_report = std::chrono::steady_clock::now();
    }
  }
  playing.join();
  line.finish();
  if (failure) {
    std::rethrow_exception(failure);
  }
  const auto done = player.progress();
  std::cout << "played " << done.published << " messages";
  if (done.refused > 0) {
    std::cout << ", " << done.refused << " refused by DDS";
  }
  std::cout << std::endl;
  if (interrupted) {
    return kExitInterrupted;
  }
  if (file_info.truncated) {
    std::cerr << "wbi play: " << truncation_line(player_options.file.string(), file_info) << "\n";
    return kExitError;
  }
  return kExitOk;
}

}  // namespace wbi::cli
