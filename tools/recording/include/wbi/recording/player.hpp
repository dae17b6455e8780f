// Replays an MCAP recording onto DDS: the engine of `wbi play`.
//
// Messages go out in log-time order at their recorded spacing divided by
// `rate`, each on its channel's topic (or its remapped name) with the type of
// its schema name and the QoS of its channel metadata (channel_qos.hpp). The
// payloads are the recorded CDR bytes, unchanged.
//
// Control, from any thread: pause(), resume(), toggle_pause(), step() (while
// paused: publish the next message now), quit(). After a pause the recorded
// spacing resumes from the last message published.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>

namespace wbi::recording {

struct PlayerOptions {
  std::filesystem::path file;
  double rate = 1.0;            // > 0; 2: twice as fast
  bool loop = false;            // start over at the end, until quit()
  double start_offset_s = 0.0;  // skip the first seconds of the recording
  std::string topics_pattern;   // play only topics that fully match this regex; empty: all
  std::map<std::string, std::string> remap;  // recorded topic -> published topic
  // Publish a SimulationClock on clock_topic carrying the recording's log time,
  // clock_rate_hz times per recorded second (the recorded clock_topic is then not replayed).
  bool clock = false;
  double clock_rate_hz = 100.0;
  std::string clock_topic = "wbi/clock";
  // Before the first message: wait up to this long for every topic to have a
  // subscriber, and for reliable topics have their first message acknowledged
  // before timing starts. 0: start at once.
  std::chrono::nanoseconds wait_for_subscribers{0};
  // The last stretch of each wait is spun rather than slept, for timing accuracy.
  std::chrono::nanoseconds spin{200'000};
  // > 0: run() plays at this SCHED_FIFO priority (1-99), so that other work
  // on a loaded machine does not delay its messages; a warning, not an error,
  // where the OS refuses (no CAP_SYS_NICE or rtprio limit). 0: normal scheduling.
  int realtime_priority = 0;
  std::function<void(const std::string&)> log;  // warnings, one line each; may be empty
};

struct PlayerProgress {
  std::uint64_t published = 0;  // messages handed to DDS
  std::uint64_t refused = 0;    // messages DDS did not accept
  std::uint64_t clock_ticks = 0;
  double position_s = 0.0;  // log time of the last message, from the recording's start
  double duration_s = 0.0;  // of the recording
  bool paused = false;
  std::uint64_t loops = 0;  // completed passes
};

class Player {
 public:
  // Opens the file and creates one publisher per played topic. Throws
  // wbi::mcap::FormatError for a corrupt file, std::invalid_argument for bad
  // options or a recording with nothing to play.
  Player(dds::Participant& participant, PlayerOptions options);
  ~Player();
  Player(const Player&) = delete;
  Player& operator=(const Player&) = delete;

  // Plays to the end (forever with loop) or until quit(). Call once.
  void run();

  void pause();
  void resume();
  void toggle_pause();
  void step();
  void quit();

  PlayerProgress progress() const;
  // The topics published, after remapping, with their types.
  std::vector<std::pair<std::string, std::string>> topics() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::recording
