// Records DDS topics to MCAP: the engine of `wbi record`.
//
// Topics are found through DDS discovery, also those that appear after the
// start. Each sample's CDR payload is written with
//   log time     = system time (ns since the Unix epoch) when it was received,
//   publish time = its Header.stamp_ns when the type starts with a Header
//                  (every wbi message but SimulationClock and the model
//                  request/reply), else the log time;
// one Schema per type (encoding "omgidl", the type's self-contained IDL text),
// one Channel per topic (message encoding "cdr", the writers' QoS in its
// metadata, see channel_qos.hpp).
//
// DDS callbacks copy each sample into a bounded queue; one writer thread
// empties it into the file, flushes it at least every flush_period (a killed
// recorder loses at most that much) and looks for new topics. A full queue
// drops samples and counts them (progress().dropped): never silently.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/mcap/format.hpp>
#include <wbi/recording/topic_loss.hpp>

namespace wbi::recording {

struct RecorderOptions {
  // With split_size_bytes 0 the one file; else the files are
  // <stem>_0<ext>, <stem>_1<ext>, ... beside it.
  std::filesystem::path output;
  // Topics to record: names that fully match any of these ECMAScript regexes.
  // Empty: every topic.
  std::vector<std::string> topic_patterns;
  // Topics not to record (full match), applied after topic_patterns. Empty: none.
  std::string exclude_pattern;
  std::uint64_t split_size_bytes = 0;  // start a new file past this size; 0: never
  mcap::Compression compression = mcap::Compression::zstd;
  std::size_t queue_capacity = 16384;  // samples waiting for the writer thread
  std::chrono::milliseconds flush_period{500};
  std::chrono::milliseconds discovery_period{100};
  // Told (on the writer thread) about each topic recorded and each problem
  // that does not stop the recording, one line each. May be empty.
  std::function<void(const std::string&)> log;
};

struct RecorderProgress {
  std::uint64_t messages = 0;       // written
  std::uint64_t payload_bytes = 0;  // CDR bytes written
  std::uint64_t file_bytes = 0;     // bytes in the file(s) so far, after compression
  std::uint64_t dropped = 0;        // samples lost to a full queue
  // Samples of a second writer of a robot's stream, not recorded: a robot
  // stream is recorded from one producer (wbi/dds/producers.hpp).
  std::uint64_t foreign = 0;
  // Samples that never reached the recorder (gaps in the writers' sequence numbers): sent
  // while it could not take them in, and gone from the writer's history (a
  // stream keeps only its newest sample) when it asked again.
  std::uint64_t lost = 0;
  std::size_t queue_high_water = 0;
  std::size_t topics = 0;
  std::size_t files = 0;
  bool failed = false;  // the writer thread stopped on an error: stop() throws it
};

class Recorder {
 public:
  // Opens the (first) file and starts recording. Throws std::invalid_argument
  // for a bad regex, std::runtime_error when the file cannot be created.
  Recorder(dds::Participant& participant, RecorderOptions options);
  // Stops (see stop()).
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Stops listening, writes what is queued and closes the file with its
  // summary. Idempotent. Throws when the file cannot be written.
  void stop();

  RecorderProgress progress() const;
  // The topics that lost samples before the recorder (RecorderProgress::lost).
  std::vector<TopicLoss> losses() const;
  // The files written so far (more than one with splitting).
  std::vector<std::filesystem::path> files() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::recording
