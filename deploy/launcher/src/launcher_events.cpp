// The launcher's own events on wbi/events (docs/events.md): a process of the
// deploy file started, exited, was respawned or hung. Each names the process
// (its name in the deploy file) as its source; the participant is "wbi launch".
#include <sys/wait.h>

#include <csignal>
#include <cstring>
#include <string>

#include "launcher_impl.hpp"

namespace wbi::launch::detail {

namespace {

// "exit code 1", or "signal 9 (SIGKILL)".
std::string how_it_ended(int wait_status) {
  if (WIFEXITED(wait_status)) {
    return "exit code " + std::to_string(WEXITSTATUS(wait_status));
  }
  const int signal_number = WTERMSIG(wait_status);
  const char* name = sigabbrev_np(signal_number);
  return "signal " + std::to_string(signal_number) +
         (name != nullptr ? std::string(" (SIG") + name + ")" : std::string());
}

}  // namespace

void Launcher::start_events() {
  if (!event_pump_) {
    event_pump_.emplace(participant(), events_, participant().name());
  }
}

void Launcher::tell(EventSeverity severity, EventKind kind, const Managed& process,
                    const std::string& text) {
  events_.emit(severity, kind, text, {}, {}, process.spec->name);
}

// A clean end is info: exit code 0, or the SIGTERM the launcher sent when it
// stopped the process. Anything else (a crash, a kill, a failure) is an error.
void Launcher::tell_exit(const Managed& process, int wait_status) {
  const bool clean =
      (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0) ||
      (process.stopped_by_us && WIFSIGNALED(wait_status) && WTERMSIG(wait_status) == SIGTERM);
  tell(clean ? EventSeverity::info : EventSeverity::error, EventKind::process_exited, process,
       "pid " + std::to_string(process.pid) + " ended with " + how_it_ended(wait_status) +
           (process.stopped_by_us ? " (stopped by the launcher)" : ""));
}

}  // namespace wbi::launch::detail
