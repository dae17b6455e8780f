// Real-time (SCHED_FIFO) scheduling for the calling thread, for as long as a
// RealtimeScope lives. The player's timing is only as good as its wake-ups: on
// a loaded machine a normal thread waits behind others for its core, a
// SCHED_FIFO one preempts them. Needs CAP_SYS_NICE or an RLIMIT_RTPRIO of at
// least the priority; without it the thread keeps its policy and refusal()
// says why, so the caller can warn instead of failing.
#pragma once

#include <string>

namespace wbi::recording {

class RealtimeScope {
 public:
  // 0: leaves the thread as it is. Throws std::invalid_argument outside
  // [0, the highest SCHED_FIFO priority] (99 on Linux).
  explicit RealtimeScope(int priority);
  ~RealtimeScope();  // restores the thread's previous policy and priority
  RealtimeScope(const RealtimeScope&) = delete;
  RealtimeScope& operator=(const RealtimeScope&) = delete;

  bool active() const { return active_; }
  // Why a requested priority was not applied; empty when it was, or when none was asked.
  const std::string& refusal() const { return refusal_; }

  // Throws std::invalid_argument, naming the option, for a priority out of range.
  static void check_priority(int priority, const char* option);

 private:
  bool active_ = false;
  int previous_policy_ = 0;
  int previous_priority_ = 0;
  std::string refusal_;
};

}  // namespace wbi::recording
