// EventPump: publishes an EventLog's events on wbi/events from a thread of
// its own, so that whoever emits (a control loop, a DDS callback) never waits
// on DDS. It looks for new events every `poll` (5 ms: an event is on the wire
// within about that), and sends what is left when it is destroyed, waiting a
// moment (kFinalAckTimeout) for the readers to acknowledge it: the last events
// of a process that ends (its exit, a divergence) would otherwise go down with
// its participant before a reader fetched them.
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
  // How long the destructor waits for the matched readers' acknowledgments
  // (a reader that is stopped, say by SIGSTOP, delays an exit by this much).
  static constexpr std::chrono::milliseconds kFinalAckTimeout{500};

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
  // The same, then waits until every matched reader acknowledged every event
  // sent so far, at most `timeout`. False on timeout.
  bool flush_acknowledged(std::chrono::nanoseconds timeout);
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
