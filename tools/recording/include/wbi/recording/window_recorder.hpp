// Keeps the last seconds of DDS topics in memory and writes them to an MCAP
// file when an event of a trigger kind arrives on wbi/events: the engine of
// `wbi record --window BEFORE:AFTER --trigger KIND[,KIND...]`.
//
// Memory: every sample goes into one fixed block of bytes (a ring of records,
// window_ring.hpp), the oldest evicted to make room; the block, the batch the
// file writer copies through and an allowance for the MCAP writer's buffers
// are the whole bound (WindowMemory), fixed at the start and never exceeded.
// DDS callbacks copy a sample into the ring under the pushers' mutex (no
// allocation); one writer thread copies batches out of it without taking
// that mutex and writes them, so writing a file never stalls the DDS readers
// and the window keeps filling meanwhile.
//
// Triggers: wbi/events is always subscribed, recorded as a channel like any
// topic and read for triggers. An event of a trigger kind stamped at t (its
// Header.stamp_ns, system time) opens a file holding [t − before, t + after];
// a trigger while that file is open extends it to after past the last one.
// Events stamped before the recorder started (the topic is transient-local)
// are neither triggers nor recorded.
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
#include <wbi/vocabulary/event.hpp>

namespace wbi::recording {

// Where the bound goes. Fixed by the constructor from max_memory_bytes.
struct WindowMemory {
  std::size_t ring_bytes = 0;    // the samples of the window, record headers included
  std::size_t batch_bytes = 0;   // the writer thread's copy of a batch of records
  std::size_t writer_bytes = 0;  // allowance for the MCAP writer (chunk, compressed copy, indexes)
  std::size_t total() const { return ring_bytes + batch_bytes + writer_bytes; }
};

// The plan for a bound: throws std::invalid_argument, saying the least, when
// max_memory_bytes leaves no room for the ring.
WindowMemory window_memory(std::size_t max_memory_bytes);
// Bytes of ring a window of `before` needs at a data rate (record headers
// included): rate × (before + kTriggerSlack), since a trigger's window starts
// at its stamp, which may be up to that much before it arrives.
std::uint64_t window_bytes_needed(double ring_bytes_per_s, std::chrono::nanoseconds before);
inline constexpr std::chrono::milliseconds kTriggerSlack{1000};

struct WindowRecorderOptions {
  std::filesystem::path directory;  // created if missing; files are named by window_file_name()
  std::vector<std::string> topic_patterns;  // full-match ECMAScript regexes; empty: every topic
  std::string exclude_pattern;              // not these (wbi/events is recorded regardless)
  std::chrono::nanoseconds before{std::chrono::seconds(5)};
  std::chrono::nanoseconds after{std::chrono::seconds(2)};
  std::vector<EventKind> triggers;
  std::size_t max_memory_bytes = std::size_t{256} << 20;
  // 0: no limit. Else, before a file beyond this many would be started, the
  // oldest file this recorder wrote is deleted (files it did not write are
  // never touched).
  std::size_t max_files = 0;
  // A file kept open by triggers that keep coming is closed at this length;
  // the next trigger starts another.
  std::chrono::seconds max_file_span{600};
  mcap::Compression compression = mcap::Compression::zstd;
  std::chrono::milliseconds discovery_period{100};
  // Told (on the writer thread) about topics, triggers and files, one line each.
  std::function<void(const std::string&)> log;
};

struct WindowProgress {
  std::uint64_t received = 0;        // samples put into the ring
  std::uint64_t received_bytes = 0;  // ring bytes they took (payload + headers)
  std::size_t ring_used_bytes = 0;   // held now
  std::size_t ring_records = 0;
  double ring_span_s = 0;  // newest log time − oldest held
  std::uint64_t evicted_in_window =
      0;                              // evicted younger than before + slack: the ring is too small
  std::uint64_t too_large = 0;        // samples larger than the ring accepts (a quarter of it)
  std::uint64_t lost_to_file = 0;     // evicted before the writer thread copied them
  std::uint64_t triggers = 0;         // trigger events taken
  std::uint64_t triggers_merged = 0;  // of which extended an open file
  std::uint64_t triggers_before_start = 0;  // ignored: stamped before the recorder started
  std::uint64_t triggers_dropped = 0;       // more pending at once than the recorder queues
  std::uint64_t events = 0;                 // events received (any kind, after the start)
  std::size_t files_written = 0;
  std::size_t files_deleted = 0;  // by max_files
  bool file_open = false;
  std::size_t topics = 0;
  std::uint64_t foreign = 0;  // samples of a second writer of a robot stream, not kept
  std::uint64_t lost = 0;     // samples that never reached the recorder (RecorderProgress::lost)
  bool failed = false;        // the writer thread stopped on an error: stop() throws it
};

class WindowRecorder {
 public:
  // Starts listening. Throws std::invalid_argument for bad options (a regex,
  // no trigger, a memory bound too small), std::runtime_error when the
  // directory cannot be created.
  WindowRecorder(dds::Participant& participant, WindowRecorderOptions options);
  ~WindowRecorder();
  WindowRecorder(const WindowRecorder&) = delete;
  WindowRecorder& operator=(const WindowRecorder&) = delete;

  // Stops listening; an open file is written up to now and closed. Idempotent.
  // Throws the writer thread's error, if any.
  void stop();

  WindowProgress progress() const;
  const WindowMemory& memory() const;
  // The topics that lost samples before the recorder (WindowProgress::lost).
  std::vector<TopicLoss> losses() const;
  // The files written and still on disk (max_files deletes the oldest), oldest first.
  std::vector<std::filesystem::path> files() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// BEFORE:AFTER in seconds ("5:2", "0.5:10"). Throws std::invalid_argument
// with one line naming the text when it does not parse, or a part is
// negative or not finite.
struct WindowSpan {
  std::chrono::nanoseconds before{0};
  std::chrono::nanoseconds after{0};
};
WindowSpan parse_window(const std::string& text);
// KIND[,KIND...], names of wbi::EventKind in any case ("watchdog_trip,LIFECYCLE").
// Throws std::invalid_argument naming an unknown kind and listing the known ones.
std::vector<EventKind> parse_trigger_kinds(const std::string& text);

// "20261127-235513.123_WATCHDOG_TRIP.mcap": the trigger's stamp in UTC (to the
// millisecond; names sort by time) and its kind.
std::string window_file_name(std::uint64_t stamp_ns, EventKind kind);

}  // namespace wbi::recording
