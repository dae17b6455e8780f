#include "wbi/runtime/event_pump.hpp"

#include <wbi/msg/events.h>
#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

namespace wbi::runtime {

struct EventPump::Impl {
  Impl(dds::Participant& participant, EventLog& events, std::string default_source)
      : log(events),
        source(std::move(default_source)),
        publisher(participant, dds::topics::kEvents, dds::qos::kEvents) {
    sample.participant(participant.name().substr(0, EventRecord::kMaxName));
  }

  // One sender at a time: the pump's thread, or flush().
  void publish_queued() {
    std::lock_guard lock(mutex);
    while (log.pop(record)) {
      msg::Header& header = sample.header();
      header.robot(record.robot[0] != '\0' ? record.robot.data() : log.default_robot());
      header.stamp_ns(record.stamp_ns);
      header.seq(seq++);
      sample.source(record.source[0] != '\0' ? std::string(record.source.data()) : source);
      sample.severity(msg::to_wire(record.severity));
      sample.kind(msg::to_wire(record.kind));
      sample.subject(record.subject.data());
      sample.text(record.text.data());
      sample.suppressed(record.suppressed);
      publisher.publish(sample);
      ++published;
    }
  }

  EventLog& log;
  std::string source;
  dds::Publisher<msg::Event> publisher;
  std::mutex mutex;
  msg::Event sample;
  EventRecord record;
  std::uint64_t seq = 0;
  std::uint64_t published = 0;
};

EventPump::EventPump(dds::Participant& participant, EventLog& log, std::string source,
                     std::chrono::milliseconds poll)
    : impl_(std::make_unique<Impl>(participant, log, std::move(source))), poll_(poll) {
  thread_ = std::thread([this] { run(); });
}

EventPump::~EventPump() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  stop_requested_.notify_all();
  thread_.join();
  flush_acknowledged(kFinalAckTimeout);  // what came in since the last poll
}

void EventPump::flush() { impl_->publish_queued(); }

bool EventPump::flush_acknowledged(std::chrono::nanoseconds timeout) {
  impl_->publish_queued();
  return impl_->publisher.wait_acknowledged(timeout);
}

std::uint64_t EventPump::published() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->published;
}

void EventPump::run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    lock.unlock();
    impl_->publish_queued();
    lock.lock();
    stop_requested_.wait_for(lock, poll_, [this] { return stop_; });
  }
}

}  // namespace wbi::runtime
