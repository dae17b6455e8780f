// The status heartbeats of the components a launch runs (wbi/status: every
// component publishes one each status_period_s, 1 s by default, from a thread
// of its own): when each instance was last heard. A process whose components
// all fall silent has stopped (SIGSTOP, a debugger) or hung without dying.
#pragma once

#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/subscriber.hpp>

namespace wbi::launch {

class Heartbeats {
 public:
  using Clock = std::chrono::steady_clock;

  explicit Heartbeats(dds::Participant& participant);

  // The newest heartbeat of any of these instances; none until one was heard
  // (a process starting up) or since forget().
  std::optional<Clock::time_point> newest(const std::vector<std::string>& instances) const;
  // Forgets these instances (a process restarted: its new components are not
  // late until they have been heard once).
  void forget(const std::vector<std::string>& instances);

 private:
  mutable std::mutex mutex_;
  std::map<std::string, Clock::time_point> heard_;  // instance → arrival of its last status
  dds::Subscriber<wbi::msg::ComponentStatus> status_;
};

}  // namespace wbi::launch
