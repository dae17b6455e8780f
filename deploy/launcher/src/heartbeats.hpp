// The status heartbeats of the components a launch runs (wbi/status: every
// component publishes one each status_period_s, 1 s by default, from a thread
// of its own): when each instance was last heard, and when the loop of a
// periodic one last advanced. A process whose components all fall silent has
// stopped (SIGSTOP, a debugger) or hung without dying; one whose periodic
// loop stops counting iterations while its status thread still speaks is
// deadlocked in its loop (or waits for an input that stopped coming: a
// controller behind a silent estimator, a lockstep loop behind its robot).
#pragma once

#include <chrono>
#include <cstdint>
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

  // A periodic component whose loop has stopped counting iterations.
  struct StalledLoop {
    std::string instance;
    std::uint64_t iterations = 0;   // where its count stopped
    Clock::time_point advanced_at;  // arrival of the last status whose count had grown
  };

  explicit Heartbeats(dds::Participant& participant);

  // The newest heartbeat of any of these instances; none until one was heard
  // (a process starting up) or since forget().
  std::optional<Clock::time_point> newest(const std::vector<std::string>& instances) const;
  // Of these instances, the active periodic one whose iteration count has not
  // grown for the longest, when that is at least `timeout`. Watched only once
  // its count has grown after its first status (a loop that ran, then stopped:
  // one that waits for its first input is not counted as stalled).
  std::optional<StalledLoop> stalled_loop(const std::vector<std::string>& instances,
                                          Clock::duration timeout) const;
  // Forgets these instances (a process restarted: its new components are not
  // late until they have been heard once).
  void forget(const std::vector<std::string>& instances);

 private:
  struct Heard {
    Clock::time_point at;           // arrival of its last status
    bool looping = false;           // active, periodic, and its count grew once
    std::uint64_t iterations = 0;   // in its last status
    Clock::time_point advanced_at;  // arrival of the last status whose count had grown
  };

  mutable std::mutex mutex_;
  std::map<std::string, Heard> heard_;  // by instance
  dds::Subscriber<wbi::msg::ComponentStatus> status_;
};

}  // namespace wbi::launch
