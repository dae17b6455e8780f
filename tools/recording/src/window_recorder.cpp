#include "wbi/recording/window_recorder.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <iomanip>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <sys/resource.h>
#include <unistd.h>

#include <wbi/msg/events.h>
#include <wbi/dds/topics.hpp>
#include <wbi/mcap/writer.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include <wbi/recording/topic_subscriptions.hpp>
#include "event_cdr.hpp"
#include "topic_filter.hpp"
#include "window_files.hpp"
#include "window_ring.hpp"

namespace wbi::recording {

namespace {

// The writer's copy out of the ring per read (no lock: window_ring.hpp).
constexpr std::size_t kBatchBytes = std::size_t{512} << 10;
constexpr std::size_t kChunkBytes = std::size_t{512} << 10;
// The MCAP writer's buffers at kChunkBytes: the open chunk (up to a chunk and
// one sample of at most kMaxSampleBytes), its compressed copy, the codec's
// context, message indexes and the summary of a file of max_file_span.
constexpr std::size_t kWriterAllowance = std::size_t{6} << 20;
// A file is closed this long after its end, once every sample logged before
// the end has been pushed (a DDS callback takes microseconds).
constexpr std::uint64_t kCloseGraceNs = 100'000'000;
constexpr std::chrono::milliseconds kWriterWake{20};
constexpr std::size_t kMaxPendingTriggers = 64;
constexpr int kWriterNice = 10;
constexpr std::size_t kMaxTriggersNamed = 32;  // in a file's metadata
constexpr double kNsPerSecond = 1e9;

std::uint64_t ns(std::chrono::nanoseconds duration) {
  return static_cast<std::uint64_t>(duration.count());
}

std::string seconds_text(std::uint64_t nanoseconds) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << static_cast<double>(nanoseconds) / kNsPerSecond;
  return out.str();
}

struct Trigger {
  std::uint64_t time_ns = 0;  // where its window is centred: the stamp, within the slack of arrival
  EventKind kind = EventKind::lifecycle;
  std::array<char, 65> source{};
};

}  // namespace

WindowMemory window_memory(std::size_t max_memory_bytes) {
  WindowMemory memory;
  memory.batch_bytes = RingBatch(kBatchBytes).reserved_bytes();
  memory.writer_bytes = kWriterAllowance;
  const std::size_t fixed = memory.batch_bytes + memory.writer_bytes;
  const std::size_t least = fixed + std::size_t{4} * WindowRing::kMaxSampleBytes;
  if (max_memory_bytes < least) {
    throw std::invalid_argument("--max-memory " + std::to_string(max_memory_bytes >> 20) +
                                " MiB is too small: at least " +
                                std::to_string((least + (1 << 20) - 1) >> 20) + " MiB");
  }
  memory.ring_bytes = max_memory_bytes - fixed;
  return memory;
}

std::uint64_t window_bytes_needed(double ring_bytes_per_s, std::chrono::nanoseconds before) {
  const double seconds = std::chrono::duration<double>(before + kTriggerSlack).count();
  return static_cast<std::uint64_t>(ring_bytes_per_s * seconds);
}

struct WindowRecorder::Impl {
  // One window's file, while it is written (writer thread only).
  struct OpenFile {
    std::filesystem::path path;
    std::optional<mcap::Writer> writer;
    std::uint64_t start_ns = 0;  // first trigger − before
    std::uint64_t end_ns = 0;    // last trigger + after
    std::uint64_t first_trigger_ns = 0;
    std::uint64_t last_trigger_ns = 0;
    std::uint64_t lost_at_open = 0;          // the ring's lost_to_reader() when it opened
    std::vector<std::uint16_t> channel_ids;  // per topic; 0: not in this file yet
    std::vector<std::uint32_t> sequences;
    std::string triggers;  // "KIND source @ time; ..." for the metadata
    std::size_t trigger_count = 0;
    WindowRing::ReadEnd last_read = WindowRing::ReadEnd::caught_up;
  };

  WindowRecorderOptions options;
  WindowMemory memory;
  TopicFilter filter;
  std::array<bool, enum_count<EventKind>()> is_trigger{};
  const std::uint64_t start_ns = system_now_ns();

  WindowRing ring;  // pushed by the DDS threads, read by the writer thread
  RingBatch batch;  // writer thread

  std::mutex trigger_mutex;
  std::condition_variable trigger_arrived;
  std::array<Trigger, kMaxPendingTriggers> pending{};
  std::size_t pending_count = 0;
  bool stop_requested = false;
  std::atomic<std::uint64_t> events{0};
  std::atomic<std::uint64_t> triggers_before_start{0};
  std::atomic<std::uint64_t> triggers_dropped{0};

  WindowFiles files;
  std::optional<OpenFile> file;  // writer thread
  std::uint64_t triggers_taken = 0;
  std::uint64_t triggers_merged = 0;
  std::size_t files_written = 0;

  TopicSubscriptions subscriptions;
  std::mutex event_mutex;  // the DDS threads of wbi/events decode into `event` in turn
  msg::Event event;

  std::thread thread;
  std::mutex stop_mutex;
  bool stopped = false;
  std::exception_ptr failure;

  mutable std::mutex progress_mutex;
  WindowProgress progress;
  std::vector<std::filesystem::path> kept_files;

  Impl(dds::Participant& p, WindowRecorderOptions o)
      : options(std::move(o)),
        memory(window_memory(options.max_memory_bytes)),
        filter(options.topic_patterns, options.exclude_pattern),
        ring(memory.ring_bytes, ns(options.before + kTriggerSlack)),
        batch(kBatchBytes),
        files(options.directory, options.max_files, options.log),
        subscriptions(
            p,
            [this](const std::string& topic) {
              return topic == dds::topics::kEvents || filter.accepts(topic);
            },
            [this](std::uint32_t index, const RecordedTopic& topic, std::uint64_t log_time,
                   std::uint64_t publish_time, std::span<const std::uint8_t> cdr) {
              on_sample(index, topic, log_time, publish_time, cdr);
            },
            options.log) {
    if (options.triggers.empty()) {
      throw std::invalid_argument("a windowed recorder needs at least one trigger kind");
    }
    if (options.before.count() < 0 || options.after.count() < 0) {
      throw std::invalid_argument("a window's before and after must be >= 0");
    }
    for (const EventKind kind : options.triggers) {
      is_trigger[static_cast<std::size_t>(kind)] = true;
    }
  }

  void log(const std::string& line) const {
    if (options.log) {
      options.log(line);
    }
  }

  // DDS threads: the hot path. No allocation: a copy into the ring (and,
  // for the rare events, their decoding).
  void on_sample(std::uint32_t index, const RecordedTopic& topic, std::uint64_t log_time,
                 std::uint64_t publish_time, std::span<const std::uint8_t> cdr) {
    const bool is_event = topic.topic.name == dds::topics::kEvents;
    if (is_event && publish_time < start_ns) {
      on_event_before_start(cdr);  // replayed by transient-local durability: not recorded
      return;
    }
    ring.push(index, log_time, publish_time, cdr);
    if (is_event) {
      std::lock_guard lock(event_mutex);
      if (decode_event(cdr, event)) {
        on_event(log_time);
      }
    }
  }

  void on_event_before_start(std::span<const std::uint8_t> cdr) {
    std::lock_guard lock(event_mutex);
    if (decode_event(cdr, event)) {
      const auto kind = msg::from_wire(event.kind());
      if (kind && is_trigger[static_cast<std::size_t>(*kind)]) {
        triggers_before_start.fetch_add(1, std::memory_order_relaxed);
      }
    }
  }

  // A DDS thread of wbi/events, per event from after the start (in `event`,
  // event_mutex held).
  void on_event(std::uint64_t arrival) {
    const std::int64_t stamp = event.header().stamp_ns();
    events.fetch_add(1, std::memory_order_relaxed);
    const auto kind = msg::from_wire(event.kind());
    if (!kind || !is_trigger[static_cast<std::size_t>(*kind)]) {
      return;
    }
    // The window is centred on the stamp, but never more than the slack
    // before the arrival (a sender's clock may be off) nor after it.
    const std::uint64_t slack = ns(kTriggerSlack);
    Trigger trigger;
    trigger.time_ns = std::clamp(static_cast<std::uint64_t>(stamp),
                                 arrival > slack ? arrival - slack : 0, arrival);
    trigger.kind = *kind;
    const char* source = event.source().c_str();
    std::copy_n(source, std::min(std::strlen(source), trigger.source.size() - 1),
                trigger.source.begin());
    {
      std::lock_guard lock(trigger_mutex);
      if (pending_count == pending.size()) {
        triggers_dropped.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      pending[pending_count++] = trigger;
    }
    trigger_arrived.notify_one();
  }

  // --- writer thread -------------------------------------------------------

  void open_file(const Trigger& trigger) {
    file.emplace();
    OpenFile& opened = *file;
    opened.path = files.start(trigger.time_ns, trigger.kind);
    mcap::WriterOptions writer_options;
    writer_options.compression = options.compression;
    writer_options.chunk_size = kChunkBytes;
    opened.writer.emplace(WindowFiles::part_path(opened.path), writer_options);
    const std::uint64_t before = ns(options.before);
    opened.start_ns = trigger.time_ns > before ? trigger.time_ns - before : 0;
    opened.end_ns = trigger.time_ns + ns(options.after);
    opened.first_trigger_ns = trigger.time_ns;
    ring.start_reading(opened.start_ns);
    opened.lost_at_open = ring.lost_to_reader();
    add_trigger(trigger);
    log("window: " + std::string(to_string(trigger.kind)) + " from '" + trigger.source.data() +
        "': writing " + file->path.string());
  }

  void add_trigger(const Trigger& trigger) {
    ++triggers_taken;
    ++file->trigger_count;
    file->last_trigger_ns = trigger.time_ns;
    file->end_ns = std::max(file->end_ns, trigger.time_ns + ns(options.after));
    if (file->trigger_count <= kMaxTriggersNamed) {
      file->triggers += std::string(file->triggers.empty() ? "" : "; ") + to_string(trigger.kind) +
                        " " + trigger.source.data() + " @ " + std::to_string(trigger.time_ns);
    }
  }

  void take(const Trigger& trigger) {
    if (file && trigger.time_ns < file->first_trigger_ns + ns(options.max_file_span)) {
      ++triggers_merged;
      add_trigger(trigger);
      log("window: " + std::string(to_string(trigger.kind)) + " from '" + trigger.source.data() +
          "': " + file->path.filename().string() + " extended to " +
          seconds_text(file->end_ns - file->first_trigger_ns) + " s after its first trigger");
      return;
    }
    if (file) {  // longer than max_file_span: ends here, the new file overlaps it
      file->end_ns = system_now_ns();
      finish_file();
    }
    open_file(trigger);
  }

  std::uint16_t channel_for(std::uint32_t index) {
    file->channel_ids.resize(subscriptions.size(), 0);
    file->sequences.resize(subscriptions.size(), 0);
    if (file->channel_ids[index] == 0) {
      const RecordedTopic& topic = subscriptions[index];
      const std::uint16_t schema =
          topic.idl_text.empty() ? 0 : file->writer->add_schema(topic.topic.type, topic.idl_text);
      file->channel_ids[index] =
          file->writer->add_channel(schema, topic.topic.name, "cdr", topic.metadata);
    }
    return file->channel_ids[index];
  }

  // Copies what the ring holds for the open file into it, batch by batch, the
  // ring's lock held only for each copy.
  void pump_file() {
    for (;;) {
      file->last_read = ring.read(batch, file->end_ns);
      for (std::size_t i = 0; i < batch.size(); ++i) {
        const auto entry = batch[i];
        const std::uint32_t source = entry.sample.source;
        if (source >= subscriptions.size()) {
          continue;  // cannot be: a validated record names a subscribed topic
        }
        const std::uint16_t channel = channel_for(source);  // sizes sequences too
        file->writer->write(channel, file->sequences[source]++, entry.sample.log_time,
                            entry.sample.publish_time, entry.bytes);
      }
      if (file->last_read != WindowRing::ReadEnd::batch_full) {
        return;
      }
    }
  }

  void finish_file() {
    pump_file();
    const std::uint64_t lost = ring.lost_to_reader() - file->lost_at_open;
    ring.stop_reading();
    const auto& stats = file->writer->statistics();
    const std::uint64_t messages = stats.messages;
    file->writer->write_metadata("wbi_window",
                                 {{"before_s", seconds_text(ns(options.before))},
                                  {"after_s", seconds_text(ns(options.after))},
                                  {"start_ns", std::to_string(file->start_ns)},
                                  {"end_ns", std::to_string(file->end_ns)},
                                  {"first_trigger_ns", std::to_string(file->first_trigger_ns)},
                                  {"last_trigger_ns", std::to_string(file->last_trigger_ns)},
                                  {"trigger_count", std::to_string(file->trigger_count)},
                                  {"triggers", file->triggers},
                                  {"lost_samples", std::to_string(lost)}});
    file->writer->close();
    file->writer.reset();
    files.finish(file->path);
    ++files_written;
    log("window: wrote " + file->path.string() + " (" + std::to_string(messages) + " messages, " +
        std::to_string(file->trigger_count) +
        (file->trigger_count == 1 ? " trigger" : " triggers") +
        (lost > 0 ? ", " + std::to_string(lost) + " samples lost: the ring overran the writer"
                  : std::string()) +
        ")");
    file.reset();
  }

  bool file_complete() const {
    return file->last_read != WindowRing::ReadEnd::batch_full &&
           system_now_ns() >= file->end_ns + kCloseGraceNs;
  }

  // Waits for triggers (or the next round), and returns those that came.
  std::size_t wait_for_triggers(std::array<Trigger, kMaxPendingTriggers>& out, bool& stop) {
    std::unique_lock lock(trigger_mutex);
    trigger_arrived.wait_for(lock, kWriterWake,
                             [&] { return pending_count > 0 || stop_requested; });
    const std::size_t count = pending_count;
    std::copy_n(pending.begin(), count, out.begin());
    pending_count = 0;
    stop = stop_requested;
    return count;
  }

  void publish_progress() {
    WindowProgress now;
    const RingStats ring_now = ring.stats();
    now.received = ring_now.pushed;
    now.received_bytes = ring_now.pushed_bytes;
    now.ring_used_bytes = ring_now.used_bytes;
    now.ring_records = ring_now.records;
    const std::uint64_t oldest = ring_now.oldest_log_time;
    const std::uint64_t system_now = system_now_ns();
    now.ring_span_s = oldest == 0 || oldest > system_now
                          ? 0.0
                          : static_cast<double>(system_now - oldest) / kNsPerSecond;
    now.evicted_in_window = ring_now.evicted_in_window;
    now.too_large = ring_now.too_large;
    now.lost_to_file = ring.lost_to_reader();
    now.triggers = triggers_taken;
    now.triggers_merged = triggers_merged;
    now.triggers_before_start = triggers_before_start.load(std::memory_order_relaxed);
    now.triggers_dropped = triggers_dropped.load(std::memory_order_relaxed);
    now.events = events.load(std::memory_order_relaxed);
    now.files_written = files_written;
    now.files_deleted = files.deleted();
    now.file_open = file.has_value();
    now.topics = subscriptions.size();
    now.foreign = subscriptions.foreign();
    now.lost = subscriptions.lost();
    std::lock_guard lock(progress_mutex);
    progress = now;
    kept_files.assign(files.kept().begin(), files.kept().end());
  }

  void run() {
    // Compressing a window's backlog is a burst of CPU: the DDS threads that
    // fill the ring go first (a robot stream keeps one sample: a reader that
    // waits for the CPU loses samples). Best effort: a thread's nice value.
    static_cast<void>(setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kWriterNice));
    using clock = std::chrono::steady_clock;
    auto next_discovery = clock::now();
    std::array<Trigger, kMaxPendingTriggers> triggers{};
    bool stop = false;
    while (!stop) {
      const std::size_t count = wait_for_triggers(triggers, stop);
      if (clock::now() >= next_discovery) {
        subscriptions.discover();
        next_discovery = clock::now() + options.discovery_period;
      }
      for (std::size_t i = 0; i < count; ++i) {
        take(triggers[i]);
      }
      if (file) {
        pump_file();
        if (file_complete()) {
          finish_file();
        }
      }
      publish_progress();
    }
    subscriptions.unsubscribe_all();  // no sample arrives after this
    if (file) {
      file->end_ns = std::min(file->end_ns, system_now_ns());
      finish_file();
    }
    publish_progress();
  }
};

WindowRecorder::WindowRecorder(dds::Participant& participant, WindowRecorderOptions options)
    : impl_(std::make_unique<Impl>(participant, std::move(options))) {
  impl_->thread = std::thread([impl = impl_.get()] {
    try {
      impl->run();
    } catch (...) {
      impl->failure = std::current_exception();
      impl->subscriptions.unsubscribe_all();
      std::lock_guard lock(impl->progress_mutex);
      impl->progress.failed = true;
    }
  });
}

WindowRecorder::~WindowRecorder() {
  try {
    stop();
  } catch (...) {
    // stop() reports errors to callers that call it; a destructor cannot.
  }
}

void WindowRecorder::stop() {
  std::lock_guard lock(impl_->stop_mutex);
  if (impl_->stopped) {
    return;
  }
  impl_->stopped = true;
  {
    std::lock_guard trigger_lock(impl_->trigger_mutex);
    impl_->stop_requested = true;
  }
  impl_->trigger_arrived.notify_one();
  impl_->thread.join();
  if (impl_->failure) {
    std::rethrow_exception(impl_->failure);
  }
}

WindowProgress WindowRecorder::progress() const {
  std::lock_guard lock(impl_->progress_mutex);
  return impl_->progress;
}

const WindowMemory& WindowRecorder::memory() const { return impl_->memory; }

std::vector<TopicLoss> WindowRecorder::losses() const { return impl_->subscriptions.losses(); }

std::vector<std::filesystem::path> WindowRecorder::files() const {
  std::lock_guard lock(impl_->progress_mutex);
  return impl_->kept_files;
}

}  // namespace wbi::recording
