// The DDS side of a recorder (Recorder, WindowRecorder): finds topics through
// discovery, subscribes to those it is told to, and hands each sample to a
// sink with its log time (system time at arrival) and publish time (its
// Header.stamp_ns when the type starts with a Header, else the log time).
//
// A topic's reader follows its writers' reliability and durability; a robot's
// stream is taken from one producer (wbi/dds/producers.hpp), samples of a
// second one counted in foreign().
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <set>
#include <span>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/raw_subscriber.hpp>
#include <wbi/mcap/format.hpp>

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

  TopicSubscriptions(dds::Participant& participant, Accepts accepts, Sink sink, Log log);
  ~TopicSubscriptions();
  TopicSubscriptions(const TopicSubscriptions&) = delete;
  TopicSubscriptions& operator=(const TopicSubscriptions&) = delete;

  // Subscribes to the accepted topics that have a writer and were not seen
  // before; returns how many were added (their indexes follow the earlier ones).
  std::size_t discover();
  // No sink call runs once this returns.
  void unsubscribe_all();

  std::size_t size() const { return entries_.size(); }
  const RecordedTopic& operator[](std::size_t index) const { return entries_[index].recorded; }
  std::uint64_t foreign() const { return foreign_.load(std::memory_order_relaxed); }

 private:
  struct Entry {
    RecordedTopic recorded;
    std::unique_ptr<dds::RawSubscriber> subscriber;
  };
  void subscribe(const dds::TopicInfo& topic);
  dds::ProducerPolicy producer_policy(const std::string& topic);

  dds::Participant& participant_;
  Accepts accepts_;
  Sink sink_;
  Log log_;
  std::deque<Entry> entries_;  // a deque: DDS callbacks hold indexes, never pointers that move
  std::set<std::string> seen_topics_;  // subscribed or not accepted
  std::atomic<std::uint64_t> foreign_{0};
};

// System time now, in ns since the Unix epoch: a recorder's log time.
std::uint64_t system_now_ns();

}  // namespace wbi::recording
