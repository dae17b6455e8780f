// Private to wbi launch: the Launcher that runs one deploy file, the state it
// keeps per process, and the wake-up pipe its signal handler writes to.
#pragma once

#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/event_pump.hpp>

#include "heartbeats.hpp"
#include "wbi/launch/launcher.hpp"

namespace wbi::launch::detail {

using Clock = std::chrono::steady_clock;

extern int wake_pipe[2];  // the signal handler writes here to end a poll()

// One process of the deploy file and what became of it.
struct Managed {
  const ProcessSpec* spec = nullptr;
  pid_t pid = -1;
  int output_fd = -1;   // read end of the pipe carrying its stdout and stderr
  std::string partial;  // output not yet ended by a newline
  int restarts = 0;
  int start_retries = 0;         // starts again after a stalled start (exit kExitStartStalled)
  bool retry_start = false;      // the pending restart_at is such a start again
  std::optional<int> exit_code;  // of the last run; 128 + signal when killed
  bool stopped_by_us = false;
  std::optional<Clock::time_point> restart_at;
  std::vector<std::string> summary_lines;  // per DeployFile::summaries: its last matching line
  bool hang_reported = false;              // silent past its hang_timeout, said once
  bool heard = false;                      // a heartbeat of this start was heard (said once)
  bool running = false;                    // a components: process printed "wbi_host: running"
  std::string failure;  // why its last run failed the launch (empty: it did not), for the summary
};

class Launcher {
 public:
  Launcher(const DeployFile& deploy, const LaunchOptions& options, std::ostream& out)
      : deploy_(deploy), options_(options), out_(out), events_(rate_limit_for(deploy)) {
    for (const auto& spec : deploy.processes) {
      Managed process;
      process.spec = &spec;
      processes_.push_back(process);
    }
  }

  int run();

 private:
  void say(const std::string& text) { out_ << "[launch] " << text << std::endl; }
  std::vector<std::string> environment_for(const ProcessSpec& spec) const;
  dds::Participant& participant();
  dds::ParticipantOptions join_options() const;
  bool wait_until_ready(const Managed& process);
  bool wait_until_running(Managed& process);
  bool spawn(Managed& process);
  void pump_output(std::chrono::milliseconds timeout);
  void print_lines(Managed& process, bool flush_partial);
  void emit(Managed& process, const std::string& line);
  bool reap(bool& failed);
  bool check_hangs(bool& failed);
  bool supervise(Clock::time_point start);
  // Starts the processes whose restart is due; false when a required one cannot start.
  bool restart_due();
  void stop_all();
  void drain_output();
  void note_never_healthy();
  void print_summary();
  // The launcher's events (launcher_events.cpp): about `process`, its source.
  void start_events();
  void tell(EventSeverity severity, EventKind kind, const Managed& process,
            const std::string& text);
  void tell_exit(const Managed& process, int wait_status);

  // The EventLog's limit is per kind; the launcher speaks for every process,
  // so it gets one process's limit per process (no exit lost at a shutdown).
  static runtime::EventRateLimit rate_limit_for(const DeployFile& deploy) {
    const double processes = std::max<double>(1.0, static_cast<double>(deploy.processes.size()));
    const runtime::EventRateLimit one;
    return {.per_second = one.per_second * processes, .burst = one.burst * processes};
  }

  const DeployFile& deploy_;
  LaunchOptions options_;
  std::ostream& out_;
  std::vector<Managed> processes_;
  std::optional<dds::Participant> participant_;
  std::optional<Heartbeats> heartbeats_;  // when a process has a hang_timeout
  runtime::EventLog events_;
  std::optional<runtime::EventPump> event_pump_;  // before participant_ goes: sends the last
};

}  // namespace wbi::launch::detail
