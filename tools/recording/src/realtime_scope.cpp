#include "realtime_scope.hpp"

#include <pthread.h>
#include <sched.h>

#include <cstring>
#include <stdexcept>

namespace wbi::recording {

void RealtimeScope::check_priority(int priority, const char* option) {
  const int highest = sched_get_priority_max(SCHED_FIFO);
  if (priority < 0 || priority > highest) {
    throw std::invalid_argument(std::string(option) + " must be in [0, " + std::to_string(highest) +
                                "] (0: off), got " + std::to_string(priority));
  }
}

RealtimeScope::RealtimeScope(int priority) {
  check_priority(priority, "real-time priority");
  if (priority == 0) {
    return;
  }
  sched_param previous{};
  if (const int error = pthread_getschedparam(pthread_self(), &previous_policy_, &previous);
      error != 0) {
    refusal_ = std::strerror(error);
    return;
  }
  previous_priority_ = previous.sched_priority;
  sched_param wanted{};
  wanted.sched_priority = priority;
  if (const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &wanted); error != 0) {
    refusal_ = std::string("SCHED_FIFO ") + std::to_string(priority) + ": " + std::strerror(error) +
               " (needs CAP_SYS_NICE or an rtprio limit)";
    return;
  }
  active_ = true;
}

RealtimeScope::~RealtimeScope() {
  if (active_) {
    sched_param previous{};
    previous.sched_priority = previous_priority_;
    pthread_setschedparam(pthread_self(), previous_policy_, &previous);
  }
}

}  // namespace wbi::recording
