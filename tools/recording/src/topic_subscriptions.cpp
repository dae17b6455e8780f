#include <wbi/recording/topic_subscriptions.hpp>

#include <chrono>
#include <stdexcept>

#include <wbi/dds/topics.hpp>
#include <wbi/msg/idl_text.hpp>

#include "channel_qos.hpp"
#include "source_stamp.hpp"

namespace wbi::recording {

std::uint64_t system_now_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

TopicSubscriptions::TopicSubscriptions(dds::Participant& participant, Accepts accepts, Sink sink,
                                       Log log, Readers readers)
    : participant_(participant),
      accepts_(std::move(accepts)),
      sink_(std::move(sink)),
      log_(std::move(log)),
      readers_(readers) {}

TopicSubscriptions::~TopicSubscriptions() { unsubscribe_all(); }

std::size_t TopicSubscriptions::discover() {
  std::lock_guard lock(mutex_);
  const std::size_t before = entries_.size();
  for (const auto& topic : participant_.discovered_topics()) {
    if (topic.writers == 0 || seen_topics_.count(topic.name) != 0) {
      continue;  // nothing to record yet, or already handled
    }
    seen_topics_.insert(topic.name);
    if (accepts_(topic.name)) {
      add(topic);
      if (readers_ == Readers::at_discovery) {
        start_reader(entries_.back(), static_cast<std::uint32_t>(entries_.size() - 1));
      }
    }
  }
  return entries_.size() - before;
}

void TopicSubscriptions::unsubscribe_all() {
  std::lock_guard lock(mutex_);
  for (auto& entry : entries_) {
    stop_reader(entry);        // no callback runs after this
    entry.opens = -1'000'000;  // and no open() starts one again
  }
}

std::size_t TopicSubscriptions::size() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

const RecordedTopic& TopicSubscriptions::operator[](std::size_t index) const {
  std::lock_guard lock(mutex_);
  return entries_.at(index).recorded;  // a deque: the reference stays valid as topics are added
}

void TopicSubscriptions::open(std::size_t index) {
  std::lock_guard lock(mutex_);
  Entry& entry = entries_.at(index);
  if (++entry.opens == 1 && readers_ == Readers::on_demand) {
    start_reader(entry, static_cast<std::uint32_t>(index));
  }
}

void TopicSubscriptions::close(std::size_t index) {
  std::lock_guard lock(mutex_);
  Entry& entry = entries_.at(index);
  if (--entry.opens == 0 && readers_ == Readers::on_demand) {
    stop_reader(entry);  // waits for a running callback, which never takes mutex_
  }
}

void TopicSubscriptions::stop_reader(Entry& entry) {
  if (entry.subscriber) {
    entry.lost_by_earlier_readers += static_cast<std::uint64_t>(entry.subscriber->samples_lost());
    entry.subscriber.reset();
  }
}

std::uint64_t TopicSubscriptions::Entry::lost() const {
  return lost_by_earlier_readers +
         (subscriber ? static_cast<std::uint64_t>(subscriber->samples_lost()) : 0);
}

std::uint64_t TopicSubscriptions::lost() const {
  std::lock_guard lock(mutex_);
  std::uint64_t lost = 0;
  for (const auto& entry : entries_) {
    lost += entry.lost();
  }
  return lost;
}

std::vector<TopicLoss> TopicSubscriptions::losses() const {
  std::lock_guard lock(mutex_);
  std::vector<TopicLoss> losses;
  for (const auto& entry : entries_) {
    if (const std::uint64_t lost = entry.lost(); lost > 0) {
      losses.push_back({entry.recorded.topic.name, lost});
    }
  }
  return losses;
}

void TopicSubscriptions::add(const dds::TopicInfo& topic) {
  Entry& entry = entries_.emplace_back();
  RecordedTopic& recorded = entry.recorded;
  recorded.topic = topic;
  recorded.metadata = channel_metadata(topic);
  try {
    recorded.idl_text = msg::idl_text_for(topic.type);
  } catch (const std::invalid_argument&) {
    if (log_) {
      log_("warning: " + topic.name + ": type " + topic.type +
           " is not a wbi type; recorded without schema");
    }
  }
  recorded.has_header =
      !recorded.idl_text.empty() && starts_with_header(topic.type, recorded.idl_text);
  if (log_) {
    log_("recording " + topic.name + " [" + topic.type + "] " +
         recorded.metadata.at("reliability") + ", " + recorded.metadata.at("durability"));
  }
}

void TopicSubscriptions::start_reader(Entry& entry, std::uint32_t index) {
  const RecordedTopic& recorded = entry.recorded;
  entry.subscriber = std::make_unique<dds::RawSubscriber>(
      participant_, recorded.topic,
      [this, index, topic_entry = &recorded](const dds::RawSample& sample) {
        const std::uint64_t received = system_now_ns();
        std::uint64_t published = received;
        if (topic_entry->has_header) {
          if (const auto stamp = header_stamp_ns(sample.cdr); stamp && *stamp >= 0) {
            published = static_cast<std::uint64_t>(*stamp);
          }
        }
        sink_(index, *topic_entry, received, published, sample.cdr);
      },
      producer_policy(recorded.topic.name));
}

// A robot's stream is recorded from one writer; a restarted producer is
// taken once the one before is gone, so both incarnations are recorded.
dds::ProducerPolicy TopicSubscriptions::producer_policy(const std::string& topic) {
  if (!dds::topics::is_single_producer_stream(topic)) {
    return {};
  }
  return dds::ProducerPolicy::one([this](const dds::ProducerEvent& event) {
    if (event.kind == dds::ProducerEvent::Kind::foreign_sample) {
      foreign_.fetch_add(1, std::memory_order_relaxed);
    }
  });
}

}  // namespace wbi::recording
