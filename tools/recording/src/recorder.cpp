#include "wbi/recording/recorder.hpp"

#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

#include <wbi/mcap/writer.hpp>

#include <wbi/recording/topic_subscriptions.hpp>
#include "sample_queue.hpp"
#include "topic_filter.hpp"

namespace wbi::recording {

namespace {

std::filesystem::path split_file(const std::filesystem::path& output, std::size_t index) {
  auto name = output.stem().string() + "_" + std::to_string(index) + output.extension().string();
  return output.parent_path() / name;
}

}  // namespace

struct Recorder::Impl {
  dds::Participant& participant;
  RecorderOptions options;
  TopicFilter filter;
  SampleQueue queue;

  TopicSubscriptions subscriptions;

  // Writer-thread state.
  std::optional<mcap::Writer> writer;
  std::vector<std::uint16_t> channel_ids;  // per subscription, in the open file
  std::vector<std::uint32_t> sequences;    // per subscription, MCAP sequence
  std::uint64_t closed_files_bytes = 0;

  std::thread thread;
  std::atomic<bool> stop_requested{false};
  std::mutex stop_mutex;
  bool stopped = false;
  std::exception_ptr failure;  // from the writer thread, rethrown by stop()

  mutable std::mutex progress_mutex;
  RecorderProgress progress;
  std::vector<std::filesystem::path> files;

  Impl(dds::Participant& p, RecorderOptions o)
      : participant(p),
        options(std::move(o)),
        filter(options.topic_patterns, options.exclude_pattern),
        queue(options.queue_capacity),
        subscriptions(
            p, [this](const std::string& topic) { return filter.accepts(topic); },
            [this](std::uint32_t index, const RecordedTopic& /*topic*/, std::uint64_t log_time,
                   std::uint64_t publish_time, std::span<const std::uint8_t> cdr) {
              queue.push(index, log_time, publish_time, cdr);
            },
            options.log) {}

  void log(const std::string& line) const {
    if (options.log) {
      options.log(line);
    }
  }

  void open_file() {
    mcap::WriterOptions writer_options;
    writer_options.compression = options.compression;
    const auto path =
        options.split_size_bytes == 0 ? options.output : split_file(options.output, files.size());
    writer.emplace(path, writer_options);
    for (std::size_t i = 0; i < subscriptions.size(); ++i) {  // a split file repeats every channel
      add_channel(i);
    }
    std::lock_guard lock(progress_mutex);
    files.push_back(path);
    progress.files = files.size();
  }

  void add_channel(std::size_t index) {
    const RecordedTopic& topic = subscriptions[index];
    const std::uint16_t schema =
        topic.idl_text.empty() ? 0 : writer->add_schema(topic.topic.type, topic.idl_text);
    channel_ids.resize(subscriptions.size());
    sequences.resize(subscriptions.size());
    channel_ids[index] = writer->add_channel(schema, topic.topic.name, "cdr", topic.metadata);
  }

  void discover() {
    const std::size_t first_new = subscriptions.size();
    if (subscriptions.discover() == 0) {
      return;
    }
    for (std::size_t i = first_new; i < subscriptions.size(); ++i) {
      add_channel(i);
    }
    std::lock_guard lock(progress_mutex);
    progress.topics = subscriptions.size();
  }

  void write(const QueuedSample& sample) {
    split_if_large();  // here, not after a drain: a new file starts with a message, never empty
    writer->write(channel_ids[sample.source], sequences[sample.source]++, sample.log_time,
                  sample.publish_time, sample.bytes);
  }

  void update_progress() {
    const auto& stats = writer->statistics();
    std::lock_guard lock(progress_mutex);
    progress.file_bytes = closed_files_bytes + stats.file_bytes;
    progress.dropped = queue.dropped();
    progress.foreign = subscriptions.foreign();
    progress.lost = subscriptions.lost();
    progress.queue_high_water = queue.high_water();
  }

  void split_if_large() {
    if (options.split_size_bytes == 0 ||
        writer->statistics().file_bytes < options.split_size_bytes) {
      return;
    }
    writer->close();
    closed_files_bytes += writer->statistics().file_bytes;
    writer.reset();
    open_file();
  }

  void run() {
    using clock = std::chrono::steady_clock;
    auto next_discovery = clock::now();
    auto next_flush = clock::now() + options.flush_period;
    std::uint64_t messages = 0;
    std::uint64_t payload = 0;
    auto consume = [&](const QueuedSample& sample) {
      write(sample);
      ++messages;
      payload += sample.bytes.size();
    };
    auto publish_counts = [&] {
      update_progress();
      std::lock_guard lock(progress_mutex);
      progress.messages = messages;
      progress.payload_bytes = payload;
    };
    while (!stop_requested) {
      queue.drain(consume, options.discovery_period / 2);
      const auto now = clock::now();
      if (now >= next_discovery) {
        discover();
        next_discovery = now + options.discovery_period;
      }
      if (now >= next_flush) {
        writer->flush();
        next_flush = now + options.flush_period;
      }
      publish_counts();
    }
    subscriptions.unsubscribe_all();  // no callback runs after this
    while (queue.drain(consume, std::chrono::nanoseconds(0)) > 0) {
    }
    writer->close();
    publish_counts();
  }
};

Recorder::Recorder(dds::Participant& participant, RecorderOptions options)
    : impl_(std::make_unique<Impl>(participant, std::move(options))) {
  impl_->open_file();
  impl_->thread = std::thread([impl = impl_.get()] {
    try {
      impl->run();
    } catch (...) {
      impl->failure = std::current_exception();
      {
        std::lock_guard lock(impl->progress_mutex);
        impl->progress.failed = true;
      }
      impl->subscriptions.unsubscribe_all();
    }
  });
}

Recorder::~Recorder() {
  try {
    stop();
  } catch (...) {
    // stop() reports errors to callers that call it; a destructor cannot.
  }
}

void Recorder::stop() {
  std::lock_guard lock(impl_->stop_mutex);
  if (impl_->stopped) {
    return;
  }
  impl_->stopped = true;
  impl_->stop_requested = true;
  impl_->queue.wake();
  impl_->thread.join();
  if (impl_->failure) {
    std::rethrow_exception(impl_->failure);
  }
}

RecorderProgress Recorder::progress() const {
  std::lock_guard lock(impl_->progress_mutex);
  return impl_->progress;
}

std::vector<TopicLoss> Recorder::losses() const { return impl_->subscriptions.losses(); }

std::vector<std::filesystem::path> Recorder::files() const {
  std::lock_guard lock(impl_->progress_mutex);
  return impl_->files;
}

}  // namespace wbi::recording
