// The DDS side of a recorder (Recorder, WindowRecorder): finds topics through
// discovery, subscribes to those it is told to, and hands each sample to a
// sink with its log time (system time at arrival) and publish time (its
// Header.stamp_ns when the type starts with a Header, else the log time).
//
// A topic's reader follows its writers' reliability and durability; a robot's
// stream is taken from one producer (wbi/dds/producers.hpp), samples of a
// second one counted in foreign().
//
// A recorder subscribes to every topic it finds (at_discovery). A viewer that
// forwards only what its clients ask for (wbi bridge) lists the topics and
// holds a reader only between open() and close() (on_demand), so that a topic
// nobody watches costs its writers no extra reader.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/raw_subscriber.hpp>
#include <wbi/mcap/format.hpp>
#include <wbi/recording/topic_loss.hpp>

namespace wbi::recording {

// One subscribed topic, and what its MCAP channel needs.
struct RecordedTopic {
  dds::TopicInfo topic;
  std::string idl_text;  // empty: not a wbi type, recorded without schema
  mcap::KeyValues metadata;
  bool has_header = false;
};

class TopicSubscriptions {
 public:
  // Called on a DDS thread; index: the topic's position in this set (stable),
  // topic: its entry (a reference that stays valid while topics are added).
  using Sink =
      std::function<void(std::uint32_t index, const RecordedTopic& topic, std::uint64_t log_time,
                         std::uint64_t publish_time, std::span<const std::uint8_t> cdr)>;
  using Accepts = std::function<bool(const std::string& topic)>;
  using Log = std::function<void(const std::string& line)>;

  enum class Readers { at_discovery, on_demand };

  TopicSubscriptions(dds::Participant& participant, Accepts accepts, Sink sink, Log log,
                     Readers readers = Readers::at_discovery);
  ~TopicSubscriptions();
  TopicSubscriptions(const TopicSubscriptions&) = delete;
  TopicSubscriptions& operator=(const TopicSubscriptions&) = delete;

  // Adds the accepted topics that have a writer and were not seen before (and
  // subscribes to them at_discovery); returns how many were added (their
  // indexes follow the earlier ones).
  std::size_t discover();
  // on_demand: the topic's reader exists while it is opened more often than
  // closed (each open needs its close). Any thread.
  void open(std::size_t index);
  void close(std::size_t index);
  // No sink call runs once this returns.
  void unsubscribe_all();

  std::size_t size() const;
  const RecordedTopic& operator[](std::size_t index) const;
  std::uint64_t foreign() const { return foreign_.load(std::memory_order_relaxed); }
  // Samples that never reached a reader of this set and never will (gaps in
  // their writers' sequence numbers, summed over topics): published while a reader could
  // not take them in, gone from the writer's history when it asked again.
  std::uint64_t lost() const;
  // The same by topic, for the topics that lost any, in the order they were added.
  std::vector<TopicLoss> losses() const;

 private:
  struct Entry {
    RecordedTopic recorded;
    std::unique_ptr<dds::RawSubscriber> subscriber;
    int opens = 0;
    std::uint64_t lost_by_earlier_readers = 0;  // on_demand: readers closed since
    std::uint64_t lost() const;
  };
  void stop_reader(Entry& entry);
  void add(const dds::TopicInfo& topic);
  void start_reader(Entry& entry, std::uint32_t index);
  dds::ProducerPolicy producer_policy(const std::string& topic);

  dds::Participant& participant_;
  Accepts accepts_;
  Sink sink_;
  Log log_;
  const Readers readers_;
  mutable std::mutex mutex_;   // entries_ grows on discover() while others open and close
  std::deque<Entry> entries_;  // a deque: DDS callbacks hold indexes, never pointers that move
  std::set<std::string> seen_topics_;  // subscribed or not accepted
  std::atomic<std::uint64_t> foreign_{0};
};

// System time now, in ns since the Unix epoch: a recorder's log time.
std::uint64_t system_now_ns();

}  // namespace wbi::recording
