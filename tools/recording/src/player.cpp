#include "wbi/recording/player.hpp"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include <wbi/msg/status.h>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/raw_publisher.hpp>
#include <wbi/mcap/reader.hpp>

#include "channel_qos.hpp"
#include "realtime_scope.hpp"
#include "topic_filter.hpp"

namespace wbi::recording {

namespace {

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::chrono::steady_clock::time_point steady_at(std::int64_t ns) {
  return std::chrono::steady_clock::time_point(std::chrono::nanoseconds(ns));
}

}  // namespace

struct Player::Impl {
  struct Output {
    std::string topic;  // after remapping
    std::string type;
    std::string profile;
    std::unique_ptr<dds::RawPublisher> publisher;
    bool first_sent = false;
  };

  dds::Participant& participant;
  PlayerOptions options;
  mcap::Reader reader;
  std::vector<Output> outputs;
  std::vector<int> output_of_channel;  // channel id -> index into outputs, -1: not played
  std::optional<dds::Publisher<msg::SimulationClock>> clock_publisher;
  msg::SimulationClock clock_sample;
  std::uint64_t next_clock_tick = 0;
  bool clock_first_sent = false;
  std::uint64_t recording_start = 0;  // log time of the first message
  std::uint64_t play_start = 0;       // recording_start + start offset

  // Timing and control, guarded by mutex.
  mutable std::mutex mutex;
  std::condition_variable changed;
  bool paused = false;
  bool step_requested = false;
  bool quit_requested = false;
  std::int64_t base_wall = 0;  // steady ns at which log time base_log is due
  std::uint64_t base_log = 0;
  std::uint64_t last_log = 0;  // of the last event played
  PlayerProgress progress;

  Impl(dds::Participant& p, PlayerOptions o)
      : participant(p), options(std::move(o)), reader(options.file) {
    if (!(options.rate > 0.0)) {
      throw std::invalid_argument("--rate must be > 0, got " + std::to_string(options.rate));
    }
    if (options.start_offset_s < 0.0) {
      throw std::invalid_argument("--start-offset must be >= 0");
    }
    if (options.clock && !(options.clock_rate_hz > 0.0)) {
      throw std::invalid_argument("clock rate must be > 0");
    }
    RealtimeScope::check_priority(options.realtime_priority, "--realtime-priority");
    const auto& info = reader.info();
    for (const auto& warning : info.warnings) {
      log("warning: " + warning);
    }
    if (info.statistics.message_count == 0) {
      throw std::invalid_argument(options.file.string() + ": the recording holds no messages");
    }
    recording_start = info.statistics.message_start_time;
    play_start = recording_start + static_cast<std::uint64_t>(options.start_offset_s * 1e9);
    progress.duration_s = 1e-9 * static_cast<double>(info.statistics.message_end_time -
                                                     info.statistics.message_start_time);
    if (play_start > info.statistics.message_end_time) {
      // Nothing would play (and --loop would spin on empty passes).
      throw std::invalid_argument("--start-offset " + std::to_string(options.start_offset_s) +
                                  " s is past the end of the recording (" +
                                  std::to_string(progress.duration_s) + " s long)");
    }
    create_outputs();
    if (options.clock) {
      clock_publisher.emplace(participant, options.clock_topic, dds::qos::kStream);
      clock_sample.step_ns(static_cast<std::int64_t>(1e9 / options.clock_rate_hz));
      clock_sample.lockstep(false);
    }
  }

  void log(const std::string& line) const {
    if (options.log) {
      options.log(line);
    }
  }

  void create_outputs() {
    const TopicFilter filter(options.topics_pattern.empty()
                                 ? std::vector<std::string>{}
                                 : std::vector<std::string>{options.topics_pattern},
                             "");
    const auto& info = reader.info();
    output_of_channel.assign(65536, -1);
    for (const auto& [id, channel] : info.channels) {
      if (!filter.accepts(channel.topic) ||
          (options.clock && channel.topic == options.clock_topic)) {
        continue;
      }
      const auto schema = info.schemas.find(channel.schema_id);
      if (channel.message_encoding != "cdr" || schema == info.schemas.end()) {
        log("warning: not playing " + channel.topic + ": " +
            (channel.message_encoding != "cdr"
                 ? "message encoding '" + channel.message_encoding + "', not cdr"
                 : std::string("no schema, so no type to publish")));
        continue;
      }
      Output output;
      const auto remapped = options.remap.find(channel.topic);
      output.topic = remapped == options.remap.end() ? channel.topic : remapped->second;
      output.type = schema->second.name;
      output.profile = profile_for(channel.metadata);
      output.publisher = std::make_unique<dds::RawPublisher>(participant, output.topic, output.type,
                                                             output.profile);
      output_of_channel[id] = static_cast<int>(outputs.size());
      outputs.push_back(std::move(output));
    }
    for (const auto& [from, to] : options.remap) {
      bool found = false;
      for (const auto& [id, channel] : info.channels) {
        found = found || channel.topic == from;
      }
      if (!found) {
        throw std::invalid_argument("--remap " + from + ":=" + to +
                                    ": the recording has no topic '" + from + "'");
      }
    }
    if (outputs.empty() && !options.clock) {
      throw std::invalid_argument(options.file.string() + ": no topic to play" +
                                  (options.topics_pattern.empty()
                                       ? std::string()
                                       : " matches --topics '" + options.topics_pattern + "'"));
    }
  }

  void wait_for_subscribers() {
    const auto deadline = std::chrono::steady_clock::now() + options.wait_for_subscribers;
    const auto left = [&] {
      return std::max(std::chrono::nanoseconds(deadline - std::chrono::steady_clock::now()),
                      std::chrono::nanoseconds::zero());
    };
    for (auto& output : outputs) {
      if (!output.publisher->wait_for_subscribers(1, left())) {
        log("warning: no subscriber on " + output.topic + "; playing anyway");
      }
    }
    if (clock_publisher && !clock_publisher->wait_for_subscribers(1, left())) {
      log("warning: no subscriber on " + options.clock_topic + "; playing anyway");
    }
  }

  // A reader that matched just now may not have matched us yet: its
  // acknowledgement of the first sample says it has it. Timing restarts after
  // it, so that the wait does not squeeze the spacing of what follows.
  template <class Publisher>
  void confirm_first(Publisher& publisher, bool& first_sent, std::uint64_t log_time) {
    if (first_sent || options.wait_for_subscribers.count() == 0) {
      return;
    }
    first_sent = true;
    publisher.wait_acknowledged(options.wait_for_subscribers);
    std::lock_guard lock(mutex);
    rebase(log_time);
  }

  // Rebases the timing so that log time `log` is due now. Caller holds mutex.
  void rebase(std::uint64_t log_time) {
    base_wall = steady_now_ns();
    base_log = log_time;
  }

  // Blocks until the event at `log_time` is due (honouring pause and step).
  // False when playing should stop.
  bool wait_for_turn(std::uint64_t log_time) {
    std::unique_lock lock(mutex);
    for (;;) {
      if (quit_requested) {
        return false;
      }
      if (paused) {
        if (step_requested) {
          step_requested = false;
          rebase(log_time);
          return true;
        }
        changed.wait(lock);
        continue;
      }
      const auto offset = static_cast<double>(static_cast<std::int64_t>(log_time - base_log));
      const std::int64_t due = base_wall + static_cast<std::int64_t>(offset / options.rate);
      const std::int64_t now = steady_now_ns();
      if (now >= due) {
        return true;
      }
      const std::int64_t spin = options.spin.count();
      if (due - now > spin) {
        changed.wait_until(lock, steady_at(due - spin));  // woken early by pause/quit
        continue;
      }
      lock.unlock();
      while (steady_now_ns() < due) {  // the last stretch: sleeping would overshoot it
        std::this_thread::yield();
      }
      return true;
    }
  }

  void played(std::uint64_t log_time, bool clock_tick, bool accepted) {
    std::lock_guard lock(mutex);
    last_log = log_time;
    progress.position_s = 1e-9 * static_cast<double>(log_time - recording_start);
    if (clock_tick) {
      ++progress.clock_ticks;
    } else if (accepted) {
      ++progress.published;
    } else {
      ++progress.refused;
    }
  }

  bool publish_clock(std::uint64_t log_time) {
    if (!wait_for_turn(log_time)) {
      return false;
    }
    clock_sample.time_ns(static_cast<std::int64_t>(log_time));
    clock_sample.tick(next_clock_tick++);  // from 0, as the simulation's clock
    played(log_time, true, clock_publisher->publish(clock_sample));
    confirm_first(*clock_publisher, clock_first_sent, log_time);
    return true;
  }

  // One pass over the recording. False when quit.
  bool play_once() {
    {
      std::lock_guard lock(mutex);
      rebase(play_start);
    }
    const auto clock_period = static_cast<std::uint64_t>(1e9 / options.clock_rate_hz);
    std::uint64_t next_clock = play_start;
    auto cursor = reader.messages(mcap::Order::log_time);
    while (const auto* message = cursor.next()) {
      if (message->log_time < play_start) {
        continue;
      }
      while (clock_publisher && next_clock <= message->log_time) {
        if (!publish_clock(next_clock)) {
          return false;
        }
        next_clock += clock_period;
      }
      const int index = output_of_channel[message->channel->id];
      if (index < 0) {
        continue;
      }
      if (!wait_for_turn(message->log_time)) {
        return false;
      }
      Output& output = outputs[static_cast<std::size_t>(index)];
      const bool accepted = output.publisher->publish(message->data);
      played(message->log_time, false, accepted);
      confirm_first(*output.publisher, output.first_sent, message->log_time);
    }
    return true;
  }

  void run() {
    const RealtimeScope realtime(options.realtime_priority);
    if (!realtime.refusal().empty()) {
      log("warning: no real-time priority, timing will suffer under load: " + realtime.refusal());
    }
    if (options.wait_for_subscribers.count() > 0) {
      wait_for_subscribers();
    }
    while (play_once()) {
      {
        std::lock_guard lock(mutex);
        ++progress.loops;
      }
      if (!options.loop) {
        break;
      }
    }
    for (auto& output : outputs) {  // reliable readers get the tail before we go
      output.publisher->wait_acknowledged(std::chrono::seconds(1));
    }
    if (clock_publisher) {
      clock_publisher->wait_acknowledged(std::chrono::seconds(1));
    }
  }

  void set_paused(bool value) {
    {
      std::lock_guard lock(mutex);
      if (paused && !value) {
        rebase(last_log);  // the recorded spacing resumes from the last message
      }
      paused = value;
      progress.paused = value;
    }
    changed.notify_all();
  }
};

Player::Player(dds::Participant& participant, PlayerOptions options)
    : impl_(std::make_unique<Impl>(participant, std::move(options))) {}

Player::~Player() = default;

void Player::run() { impl_->run(); }

void Player::pause() { impl_->set_paused(true); }

void Player::resume() { impl_->set_paused(false); }

void Player::toggle_pause() {
  bool paused = false;
  {
    std::lock_guard lock(impl_->mutex);
    paused = impl_->paused;
  }
  impl_->set_paused(!paused);
}

void Player::step() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->step_requested = impl_->paused;
  }
  impl_->changed.notify_all();
}

void Player::quit() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->quit_requested = true;
  }
  impl_->changed.notify_all();
}

PlayerProgress Player::progress() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->progress;
}

std::vector<std::pair<std::string, std::string>> Player::topics() const {
  std::vector<std::pair<std::string, std::string>> topics;
  for (const auto& output : impl_->outputs) {
    topics.emplace_back(output.topic, output.type);
  }
  return topics;
}

}  // namespace wbi::recording
