// EventPump: publishes an EventLog's events on wbi/events from a thread of
// its own, so that whoever emits (a control loop, a DDS callback) never waits
// on DDS. It looks for new events every `poll` (5 ms: an event is on the wire
// within about that), and sends what is left when it is destroyed.
#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "wbi/runtime/event_log.hpp"

namespace wbi::dds {
class Participant;
}

namespace wbi::runtime {

class EventPump {
 public:
  // `source` names the events whose record names none (a component's
  // instance); the participant's name goes into every event. participant and
  // log must outlive the pump.
  EventPump(dds::Participant& participant, EventLog& log, std::string source,
            std::chrono::milliseconds poll = std::chrono::milliseconds(5));
  ~EventPump();
  EventPump(const EventPump&) = delete;
  EventPump& operator=(const EventPump&) = delete;

  // Publishes every queued event now (the caller's thread).
  void flush();
  std::uint64_t published() const;

 private:
  void run();

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::chrono::milliseconds poll_;
  std::mutex mutex_;
  std::condition_variable stop_requested_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace wbi::runtime
