#include "wbi/recording/recorder.hpp"

#include <atomic>
#include <deque>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include <wbi/dds/raw_subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/mcap/writer.hpp>
#include <wbi/msg/idl_text.hpp>

#include "channel_qos.hpp"
#include "sample_queue.hpp"
#include "source_stamp.hpp"
#include "topic_filter.hpp"

namespace wbi::recording {

namespace {

std::uint64_t system_now_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

std::filesystem::path split_file(const std::filesystem::path& output, std::size_t index) {
  auto name = output.stem().string() + "_" + std::to_string(index) + output.extension().string();
  return output.parent_path() / name;
}

}  // namespace

struct Recorder::Impl {
  // One recorded topic. Lives in a deque: DDS callbacks never see it, only its index.
  struct Subscription {
    dds::TopicInfo topic;
    std::string idl_text;  // empty: not a wbi type, recorded without schema
    mcap::KeyValues metadata;
    std::uint16_t channel_id = 0;
    std::uint32_t sequence = 0;
    std::unique_ptr<dds::RawSubscriber> subscriber;
  };

  dds::Participant& participant;
  RecorderOptions options;
  TopicFilter filter;
  SampleQueue queue;

  // Writer-thread state.
  std::optional<mcap::Writer> writer;
  std::deque<Subscription> subscriptions;
  std::set<std::string> seen_topics;  // subscribed or filtered out
  std::uint64_t closed_files_bytes = 0;

  std::atomic<std::uint64_t> foreign{0};  // samples of a second writer of a robot stream

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
        queue(options.queue_capacity) {}

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
    for (auto& subscription : subscriptions) {  // a split file repeats every channel
      add_channel(subscription);
    }
    std::lock_guard lock(progress_mutex);
    files.push_back(path);
    progress.files = files.size();
  }

  void add_channel(Subscription& subscription) {
    const std::uint16_t schema =
        subscription.idl_text.empty()
            ? 0
            : writer->add_schema(subscription.topic.type, subscription.idl_text);
    subscription.channel_id =
        writer->add_channel(schema, subscription.topic.name, "cdr", subscription.metadata);
  }

  void discover() {
    for (const auto& topic : participant.discovered_topics()) {
      if (topic.writers == 0 || seen_topics.count(topic.name) != 0) {
        continue;  // nothing to record yet, or already handled
      }
      seen_topics.insert(topic.name);
      if (filter.accepts(topic.name)) {
        subscribe(topic);
      }
    }
  }

  void subscribe(const dds::TopicInfo& topic) {
    Subscription& subscription = subscriptions.emplace_back();
    subscription.topic = topic;
    subscription.metadata = channel_metadata(topic);
    try {
      subscription.idl_text = msg::idl_text_for(topic.type);
    } catch (const std::invalid_argument&) {
      log("warning: " + topic.name + ": type " + topic.type +
          " is not a wbi type; recorded without schema");
    }
    const bool has_header =
        !subscription.idl_text.empty() && starts_with_header(topic.type, subscription.idl_text);
    add_channel(subscription);
    const auto index = static_cast<std::uint32_t>(subscriptions.size() - 1);
    subscription.subscriber = std::make_unique<dds::RawSubscriber>(
        participant, topic,
        [this, index, has_header](const dds::RawSample& sample) {
          const std::uint64_t received = system_now_ns();
          std::uint64_t published = received;
          if (has_header) {
            if (const auto stamp = header_stamp_ns(sample.cdr); stamp && *stamp >= 0) {
              published = static_cast<std::uint64_t>(*stamp);
            }
          }
          queue.push(index, received, published, sample.cdr);
        },
        producer_policy(topic.name));
    {
      std::lock_guard lock(progress_mutex);
      progress.topics = subscriptions.size();
    }
    log("recording " + topic.name + " [" + topic.type + "] " +
        subscription.metadata.at("reliability") + ", " + subscription.metadata.at("durability"));
  }

  // A robot's stream is recorded from one writer; a restarted producer is
  // taken once the one before is gone, so both incarnations are in the file.
  dds::ProducerPolicy producer_policy(const std::string& topic) {
    if (!dds::topics::is_single_producer_stream(topic)) {
      return {};
    }
    return dds::ProducerPolicy::one([this](const dds::ProducerEvent& event) {
      if (event.kind == dds::ProducerEvent::Kind::foreign_sample) {
        foreign.fetch_add(1, std::memory_order_relaxed);
      }
    });
  }

  void write(const QueuedSample& sample) {
    split_if_large();  // here, not after a drain: a new file starts with a message, never empty
    Subscription& subscription = subscriptions[sample.source];
    writer->write(subscription.channel_id, subscription.sequence++, sample.log_time,
                  sample.publish_time, sample.bytes);
  }

  void update_progress() {
    const auto& stats = writer->statistics();
    std::lock_guard lock(progress_mutex);
    progress.file_bytes = closed_files_bytes + stats.file_bytes;
    progress.dropped = queue.dropped();
    progress.foreign = foreign.load(std::memory_order_relaxed);
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
    for (auto& subscription : subscriptions) {
      subscription.subscriber.reset();  // no callback runs after this
    }
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
      for (auto& subscription : impl->subscriptions) {
        subscription.subscriber.reset();
      }
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

std::vector<std::filesystem::path> Recorder::files() const {
  std::lock_guard lock(impl_->progress_mutex);
  return impl_->files;
}

}  // namespace wbi::recording
