// wbi launch's supervision: starting the deploy file's processes in order,
// watching exits and hangs, respawning, stopping them all; and the signals.
#include "wbi/launch/launcher.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <wbi/runtime/process_exit.hpp>
#include <wbi/vocabulary/seconds_text.hpp>

#include "launcher_impl.hpp"

namespace wbi::launch {

namespace detail {

int wake_pipe[2] = {-1, -1};

}  // namespace detail

using detail::Clock;
using detail::wake_pipe;

namespace {

std::atomic<int> stop_signal{0};

extern "C" void on_stop_signal(int signal_number) {
  stop_signal = signal_number;
  const char byte = 1;
  [[maybe_unused]] const auto ignored = write(wake_pipe[1], &byte, 1);
}

// How many times a process whose start stalled is started again.
constexpr int kStartRetries = 3;

// Longest wait for a components: process to say it runs (configure may load
// large models) before the next process starts anyway.
constexpr double kStartTimeoutS = 60.0;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

namespace detail {

int Launcher::run() {
  const auto start = Clock::now();
  bool failed = false;
  start_events();
  if (std::any_of(processes_.begin(), processes_.end(),
                  [](const Managed& p) { return p.spec->hang_timeout_s > 0; })) {
    heartbeats_.emplace(participant());
  }
  for (auto& process : processes_) {
    if (stop_signal != 0 || !wait_until_ready(process) || !spawn(process) ||
        !wait_until_running(process)) {
      failed = stop_signal == 0;
      break;
    }
  }
  if (!failed && stop_signal == 0) {
    failed = supervise(start);
  }
  stop_all();
  drain_output();
  note_never_healthy();
  print_summary();
  if (stop_signal != 0) {
    return 130;
  }
  // A launch whose processes all ran is not enough: one that ended in error
  // (even an optional one) or never came up fails it too, so that a script
  // reads the truth from the exit code (the summary names each).
  const bool any_failure = std::any_of(processes_.begin(), processes_.end(),
                                       [](const Managed& p) { return !p.failure.empty(); });
  return failed || any_failure ? 1 : 0;
}

// A components: process whose last start never said its components run
// (wbi_host: running) did not do its part, whatever its exit code.
void Launcher::note_never_healthy() {
  for (auto& process : processes_) {
    if (process.failure.empty() && process.spec->hosts_components && process.exit_code &&
        !process.running) {
      process.failure = "never became healthy (its components did not say they run)";
    }
  }
}

namespace {

// Why a run that ended with exit_code (not 0) failed, for the summary.
std::string failure_of(int exit_code) {
  switch (exit_code) {
    case runtime::kExitConfigurationError:
      return "configuration error";
    case runtime::kExitRunFailed:
      return "its run failed its checks";
    case runtime::kExitStartStalled:
      return "its start stalled every time";
    default:
      return "ended in error";
  }
}

// Exit codes that respawning cannot change (wbi/runtime/process_exit.hpp).
bool is_final(int exit_code) {
  return exit_code == runtime::kExitConfigurationError || exit_code == runtime::kExitRunFailed;
}

// A process we stopped ended cleanly: exit 0, or SIGTERM/SIGINT's usual codes.
bool stopped_cleanly(int exit_code) {
  return exit_code == 0 || exit_code == 128 + SIGTERM || exit_code == 128 + SIGINT;
}

}  // namespace

bool Launcher::wait_until_ready(const Managed& process) {
  const auto& topics = process.spec->wait_for_topics;
  if (topics.empty()) {
    return true;
  }
  participant();
  const auto deadline = Clock::now() + seconds(process.spec->wait_timeout_s);
  for (const auto& topic : topics) {
    say(process.spec->name + ": waiting for " + topic);
    while (!participant_->wait_for_topic(topic, std::chrono::milliseconds(100))) {
      pump_output(std::chrono::milliseconds(0));
      if (stop_signal != 0) {
        return false;
      }
      // A process before this one may end meanwhile (a stalled start: started again).
      bool failed = false;
      if ((reap(failed) && failed) || !restart_due()) {
        return false;
      }
      if (Clock::now() >= deadline) {
        say(process.spec->name + ": not started: " + topic + " did not appear within " +
            seconds_text(process.spec->wait_timeout_s));
        return false;
      }
    }
  }
  return true;
}

// A components: process is started once wbi_host says its components run
// (configured and active): the next process starts only then, so that its
// wait_for cannot be met by another deployment's topics while this one is
// still starting (or refusing to: a robot whose name is taken). Returns
// false when it ended first and that fails the launch.
bool Launcher::wait_until_running(Managed& process) {
  if (!process.spec->hosts_components) {
    return true;
  }
  const auto deadline = Clock::now() + seconds(kStartTimeoutS);
  while (!process.running && stop_signal == 0) {
    pump_output(std::chrono::milliseconds(50));
    bool failed = false;
    if ((reap(failed) && failed) || !restart_due()) {
      return false;
    }
    if (process.pid <= 0 && !process.retry_start) {
      return true;  // ended, not fatal (reap said so; respawn may follow)
    }
    if (Clock::now() >= deadline) {
      say(process.spec->name + ": not running after " + seconds_text(kStartTimeoutS) +
          ": going on with the next process");
      return true;
    }
  }
  return stop_signal == 0;
}

// Collects exits; returns true when the launch must stop, with `failed` set
// when a required process failed. Each failed run's reason is kept for the
// summary and the exit code (Managed::failure).
bool Launcher::reap(bool& failed) {
  bool stop = false;
  for (auto& process : processes_) {
    if (process.pid <= 0) {
      continue;
    }
    int status = 0;
    if (waitpid(process.pid, &status, WNOHANG) != process.pid) {
      continue;
    }
    tell_exit(process, status);
    process.pid = -1;
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    process.exit_code = code;
    if (process.stopped_by_us) {
      if (stopped_cleanly(code)) {
        say(process.spec->name + ": stopped");
      } else {
        process.failure = "did not stop cleanly";
        say(process.spec->name + ": stopped with exit code " + std::to_string(code));
      }
      continue;
    }
    if (code == runtime::kExitStartStalled && process.start_retries < kStartRetries) {
      // Not the process's fault, nor a run that went wrong: it started again at once.
      ++process.start_retries;
      process.retry_start = true;
      process.restart_at = Clock::now();
      say(process.spec->name + ": its start stalled (exit code " + std::to_string(code) +
          "): starting it again, " + std::to_string(process.start_retries) + " of " +
          std::to_string(kStartRetries));
      continue;
    }
    const bool ok = code == 0;
    if (!ok) {
      process.failure = failure_of(code);
    }
    say(process.spec->name + (ok ? ": exited"
                                 : ": failed with exit code " + std::to_string(code) +
                                       (is_final(code) ? " (" + process.failure + ")" : "")));
    const bool will_respawn = !is_final(code) && process.spec->respawn.enabled &&
                              process.restarts < process.spec->respawn.max_retries;
    if (!ok && is_final(code) && process.spec->respawn.enabled) {
      say(process.spec->name + ": not respawned (starting it again cannot change that)");
    }
    // A shutdown_on_exit process that ends cleanly ends the run; one that
    // fails is respawned first when it may be (a crashed controller of an
    // experiment that ends itself).
    if (process.spec->shutdown_on_exit && (ok || !will_respawn)) {
      say(process.spec->name + " ended: stopping the launch");
      stop = true;
      failed = failed || (!ok && process.spec->required);
    } else if (will_respawn) {
      process.restart_at = Clock::now() + seconds(process.spec->respawn.delay_s);
    } else if (!ok && process.spec->required) {
      say(process.spec->name + " is required: stopping the launch");
      stop = true;
      failed = true;
    }
  }
  return stop;
}

// A process whose components' heartbeats stopped for its hang_timeout
// (stopped, or hung without dying), or one of whose periodic components
// stopped counting loop iterations for that long while its status thread
// still speaks (its loop deadlocked), is said once and handled like a
// failure: killed (SIGKILL: it may not be able to handle SIGTERM) so that
// reap() respawns it, else, when required, the launch stops. Returns true
// when the launch must stop.
bool Launcher::check_hangs(bool& failed) {
  if (!heartbeats_) {
    return false;
  }
  for (auto& process : processes_) {
    const double timeout_s = process.spec->hang_timeout_s;
    if (timeout_s <= 0 || process.pid <= 0) {
      continue;
    }
    const auto heard = heartbeats_->newest(process.spec->components);
    if (heard && !process.heard) {
      process.heard = true;  // watched from now on (a start may take any time)
      say(process.spec->name + ": heartbeat heard; hung after " + seconds_text(timeout_s) +
          " without one or without loop iterations");
    }
    if (!heard) {
      process.hang_reported = false;
      continue;
    }
    const auto timeout = seconds(timeout_s);
    std::string why;
    if (Clock::now() - *heard >= timeout) {
      const double silent_s = std::chrono::duration<double>(Clock::now() - *heard).count();
      why = "no status heartbeat from its components for " + seconds_text(silent_s) +
            " (hang_timeout " + seconds_text(timeout_s) + "): hung or stopped";
    } else if (const auto stalled = heartbeats_->stalled_loop(process.spec->components, timeout)) {
      const double still_s =
          std::chrono::duration<double>(Clock::now() - stalled->advanced_at).count();
      why = "the loop of '" + stalled->instance + "' stopped at iteration " +
            std::to_string(stalled->iterations) + " " + seconds_text(still_s) +
            " ago while its status goes on (hang_timeout " + seconds_text(timeout_s) +
            "): deadlocked, or waiting for an input that stopped";
    }
    if (why.empty()) {
      process.hang_reported = false;
      continue;
    }
    if (process.hang_reported) {
      continue;
    }
    process.hang_reported = true;
    say(process.spec->name + ": " + why);
    tell(EventSeverity::error, EventKind::process_hung, process, why);
    const bool will_respawn =
        process.spec->respawn.enabled && process.restarts < process.spec->respawn.max_retries;
    if (will_respawn) {
      say(process.spec->name + ": killed (SIGKILL) to be respawned");
      kill(-process.pid, SIGKILL);  // reap() sees the exit and respawns it
    } else if (process.spec->required) {
      say(process.spec->name + " is required: stopping the launch");
      failed = true;
      return true;
    }
  }
  return false;
}

bool Launcher::supervise(Clock::time_point start) {
  bool failed = false;
  while (stop_signal == 0) {
    pump_output(std::chrono::milliseconds(50));
    if (reap(failed) || check_hangs(failed)) {
      return failed;
    }
    if (!restart_due()) {
      return true;
    }
    const bool all_ended = std::all_of(processes_.begin(), processes_.end(), [](const Managed& p) {
      return p.pid <= 0 && !p.restart_at;
    });
    if (all_ended) {
      say("every process has ended");
      return failed;
    }
    if (options_.duration_s > 0 && Clock::now() - start >= seconds(options_.duration_s)) {
      say("duration of " + seconds_text(options_.duration_s) + " reached");
      return failed;
    }
  }
  say(std::string("interrupted (") + (stop_signal == SIGINT ? "SIGINT" : "SIGTERM") + ")");
  return failed;
}

bool Launcher::restart_due() {
  for (auto& process : processes_) {
    if (!process.restart_at || Clock::now() < *process.restart_at) {
      continue;
    }
    std::string why;
    if (process.retry_start) {
      process.retry_start = false;
      why = "start-up stalled: started again, " + std::to_string(process.start_retries) + " of " +
            std::to_string(kStartRetries);
    } else {
      ++process.restarts;
      why = "respawn " + std::to_string(process.restarts) + " of " +
            std::to_string(process.spec->respawn.max_retries);
      say(process.spec->name + ": " + why);
    }
    tell(EventSeverity::warning, EventKind::process_respawned, process, why);
    if (!spawn(process) && process.spec->required) {
      return false;
    }
  }
  return true;
}

// SIGTERM to every running process group, last started first; SIGKILL after the grace period.
void Launcher::stop_all() {
  for (auto it = processes_.rbegin(); it != processes_.rend(); ++it) {
    it->restart_at.reset();
    if (it->pid > 0) {
      it->stopped_by_us = true;
      kill(-it->pid, SIGTERM);
      kill(-it->pid, SIGCONT);  // a stopped process handles SIGTERM only once resumed
    }
  }
  const auto deadline = Clock::now() + seconds(options_.stop_grace_s);
  bool failed_ignored = false;
  while (Clock::now() < deadline && std::any_of(processes_.begin(), processes_.end(),
                                                [](const Managed& p) { return p.pid > 0; })) {
    pump_output(std::chrono::milliseconds(20));
    reap(failed_ignored);
  }
  for (auto& process : processes_) {
    if (process.pid > 0) {
      say(process.spec->name + ": did not stop within " + seconds_text(options_.stop_grace_s) +
          ": SIGKILL");
      kill(-process.pid, SIGKILL);
      int status = 0;
      waitpid(process.pid, &status, 0);
      tell_exit(process, status);
      process.exit_code = 128 + SIGKILL;
      process.failure = "did not stop within the grace period: SIGKILL";
      process.pid = -1;
    }
  }
}

}  // namespace detail

int run_launch(const DeployFile& deploy, const LaunchOptions& options, std::ostream& out) {
  if (pipe2(wake_pipe, O_CLOEXEC | O_NONBLOCK) != 0) {
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  stop_signal = 0;
  auto* previous_int = std::signal(SIGINT, on_stop_signal);
  auto* previous_term = std::signal(SIGTERM, on_stop_signal);
  int code = 1;
  try {
    code = detail::Launcher(deploy, options, out).run();
  } catch (...) {
    std::signal(SIGINT, previous_int);
    std::signal(SIGTERM, previous_term);
    throw;
  }
  std::signal(SIGINT, previous_int);
  std::signal(SIGTERM, previous_term);
  close(wake_pipe[0]);
  close(wake_pipe[1]);
  return code;
}

bool stop_when_launcher_dies() {
  const char* launcher = std::getenv(kLauncherPidVariable);
  if (launcher == nullptr || std::to_string(getppid()) != launcher) {
    return false;
  }
  if (prctl(PR_SET_PDEATHSIG, SIGTERM) != 0) {
    return false;
  }
  // The launcher may have died before prctl: then this process has another parent now.
  if (std::to_string(getppid()) != launcher) {
    raise(SIGTERM);
  }
  return true;
}

}  // namespace wbi::launch
