#include "wbi/launch/launcher.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <wbi/dds/join_options.hpp>
#include <wbi/dds/participant.hpp>

#include "heartbeats.hpp"

extern char** environ;

namespace wbi::launch {

namespace {

using Clock = std::chrono::steady_clock;

std::atomic<int> stop_signal{0};
int wake_pipe[2] = {-1, -1};  // the signal handler writes here to end a poll()

extern "C" void on_stop_signal(int signal_number) {
  stop_signal = signal_number;
  const char byte = 1;
  [[maybe_unused]] const auto ignored = write(wake_pipe[1], &byte, 1);
}

// Longest wait for a components: process to say it runs (configure may load
// large models) before the next process starts anyway.
constexpr double kStartTimeoutS = 60.0;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

std::filesystem::path own_directory() {
  std::error_code error;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path() : exe.parent_path();
}

// argv[0] next to the running `wbi` first (a build tree or an install), then on PATH.
std::string resolve_program(const std::string& program) {
  if (program.find('/') != std::string::npos) {
    return program;
  }
  const auto beside = own_directory() / program;
  if (access(beside.c_str(), X_OK) == 0) {
    return beside.string();
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const auto end = dirs.find(':', start);
    const auto candidate = std::filesystem::path(dirs.substr(start, end - start)) / program;
    if (access(candidate.c_str(), X_OK) == 0) {
      return candidate.string();
    }
    if (end == std::string::npos) {
      break;
    }
    start = end + 1;
  }
  throw std::runtime_error("program '" + program + "' not found next to wbi nor on PATH");
}

// One process of the deploy file and what became of it.
struct Managed {
  const ProcessSpec* spec = nullptr;
  pid_t pid = -1;
  int output_fd = -1;   // read end of the pipe carrying its stdout and stderr
  std::string partial;  // output not yet ended by a newline
  int restarts = 0;
  std::optional<int> exit_code;  // of the last run; 128 + signal when killed
  bool stopped_by_us = false;
  std::optional<Clock::time_point> restart_at;
  std::vector<std::string> summary_lines;  // per DeployFile::summaries: its last matching line
  bool hang_reported = false;              // silent past its hang_timeout, said once
  bool heard = false;                      // a heartbeat of this start was heard (said once)
  bool running = false;                    // a components: process printed "wbi_host: running"
};

class Launcher {
 public:
  Launcher(const DeployFile& deploy, const LaunchOptions& options, std::ostream& out)
      : deploy_(deploy), options_(options), out_(out) {
    for (const auto& spec : deploy.processes) {
      Managed process;
      process.spec = &spec;
      processes_.push_back(process);
    }
  }

  int run() {
    const auto start = Clock::now();
    bool failed = false;
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
    print_summary();
    if (stop_signal != 0) {
      return 130;
    }
    return failed ? 1 : 0;
  }

 private:
  void say(const std::string& text) { out_ << "[launch] " << text << std::endl; }

  std::vector<std::string> environment_for(const ProcessSpec& spec) const {
    std::map<std::string, std::string> env;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string entry = *e;
      const auto eq = entry.find('=');
      env[entry.substr(0, eq)] = eq == std::string::npos ? "" : entry.substr(eq + 1);
    }
    // The processes read the deploy file too, then the environment: the
    // launcher's resolved domain and QoS file, and its flags, go there, so
    // that every process joins as the launcher did (dds/README.md).
    const dds::ParticipantOptions join = join_options();
    env["WBI_DOMAIN_ID"] = std::to_string(join.domain_id);
    if (!join.qos_file.empty()) {
      env["WBI_QOS_FILE"] = join.qos_file;
    }
    const dds::JoinOverrides& flags = options_.join;
    auto joined = [](const std::vector<std::string>& list) {
      std::string text;
      for (const auto& item : list) {
        text += (text.empty() ? "" : ",") + item;
      }
      return text;
    };
    if (flags.discovery) env["WBI_DDS_DISCOVERY"] = dds::discovery_name(*flags.discovery);
    if (flags.peers || flags.discovery_server || flags.interfaces) {
      env["WBI_DDS_DISCOVERY"] = dds::discovery_name(join.discovery);
    }
    if (flags.peers) env["WBI_DDS_PEERS"] = joined(*flags.peers);
    if (flags.interfaces) env["WBI_DDS_INTERFACES"] = joined(*flags.interfaces);
    if (flags.discovery_server) env["WBI_DDS_DISCOVERY_SERVER"] = *flags.discovery_server;
    if (flags.security_directory) env["WBI_DDS_SECURITY_DIRECTORY"] = *flags.security_directory;
    // Each process joins as its own name, not as one identity for all.
    env.erase("WBI_DDS_SECURITY_IDENTITY");
    // wbi_host stops when this process dies, even by SIGKILL (apps/host/main.cpp).
    env[kLauncherPidVariable] = std::to_string(getpid());
    for (const auto& [key, value] : deploy_.environment) {
      env[key] = value;
    }
    for (const auto& [key, value] : spec.environment) {
      env[key] = value;
    }
    std::vector<std::string> entries;
    for (const auto& [key, value] : env) {
      entries.push_back(key + "=" + value);
    }
    return entries;
  }

  // The launcher's own participant (made when first needed): waits for topics,
  // hears heartbeats; the deploy's domain, QoS, network and security.
  dds::Participant& participant() {
    if (!participant_) {
      participant_.emplace(join_options());
    }
    return *participant_;
  }

  // defaults < deploy file < environment < flags (dds/README.md, "Joining a deployment").
  dds::ParticipantOptions join_options() const {
    dds::ParticipantOptions join;
    join.name = "wbi launch";
    if (deploy_.domain_id) {
      join.domain_id = *deploy_.domain_id;
    }
    join.qos_file = deploy_.qos_file.string();
    join.discovery = deploy_.discovery;
    join.network = deploy_.network;
    join.security = deploy_.security;
    dds::apply_environment(join);
    // A process's identity is its own; the launcher's is "launcher" whatever the environment says.
    join.security.identity =
        deploy_.security.identity.empty() ? "launcher" : deploy_.security.identity;
    dds::apply(options_.join, join);
    return join;
  }

  bool wait_until_ready(const Managed& process) {
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
        if (Clock::now() >= deadline) {
          say(process.spec->name + ": not started: " + topic + " did not appear within " +
              std::to_string(process.spec->wait_timeout_s) + " s");
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
  bool wait_until_running(Managed& process) {
    if (!process.spec->hosts_components) {
      return true;
    }
    const auto deadline = Clock::now() + seconds(kStartTimeoutS);
    while (!process.running && stop_signal == 0) {
      pump_output(std::chrono::milliseconds(50));
      bool failed = false;
      if (reap(failed) && failed) {
        return false;
      }
      if (process.pid <= 0) {
        return true;  // ended, not fatal (reap said so; respawn may follow)
      }
      if (Clock::now() >= deadline) {
        say(process.spec->name + ": not running after " + std::to_string(kStartTimeoutS) +
            " s: going on with the next process");
        return true;
      }
    }
    return stop_signal == 0;
  }

  bool spawn(Managed& process) {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) {
      say(process.spec->name + ": cannot create a pipe: " + std::strerror(errno));
      return false;
    }
    std::string program;
    try {
      program = resolve_program(process.spec->command.front());
    } catch (const std::exception& e) {
      say(process.spec->name + ": " + e.what());
      close(fds[0]);
      close(fds[1]);
      return false;
    }
    std::vector<std::string> args = process.spec->command;
    args.front() = program;
    std::vector<char*> argv;
    for (auto& arg : args) {
      argv.push_back(arg.data());
    }
    argv.push_back(nullptr);
    auto env_entries = environment_for(*process.spec);
    std::vector<char*> envp;
    for (auto& entry : env_entries) {
      envp.push_back(entry.data());
    }
    envp.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    // Own process group: a Ctrl-C at the terminal reaches the launcher only,
    // which then stops the processes in order.
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF);
    posix_spawnattr_setpgroup(&attributes, 0);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    const int rc =
        posix_spawn(&process.pid, program.c_str(), &actions, &attributes, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    close(fds[1]);
    if (rc != 0) {
      close(fds[0]);
      say(process.spec->name + ": cannot start " + program + ": " + std::strerror(rc));
      return false;
    }
    fcntl(fds[0], F_SETFL, O_NONBLOCK);
    process.output_fd = fds[0];
    process.exit_code.reset();
    process.restart_at.reset();
    process.hang_reported = false;
    process.heard = false;
    process.running = false;
    if (heartbeats_) {
      heartbeats_->forget(process.spec->components);  // the new ones are not late yet
    }
    say(process.spec->name + ": started (pid " + std::to_string(process.pid) + ")");
    return true;
  }

  // Reads what the processes printed, for up to `timeout`, and prints it line by line.
  void pump_output(std::chrono::milliseconds timeout) {
    std::vector<pollfd> fds{{wake_pipe[0], POLLIN, 0}};
    std::vector<Managed*> owners{nullptr};
    for (auto& process : processes_) {
      if (process.output_fd >= 0) {
        fds.push_back({process.output_fd, POLLIN, 0});
        owners.push_back(&process);
      }
    }
    if (poll(fds.data(), fds.size(), static_cast<int>(timeout.count())) <= 0) {
      return;
    }
    char buffer[4096];
    if ((fds[0].revents & POLLIN) != 0) {
      while (read(wake_pipe[0], buffer, sizeof buffer) > 0) {
      }
    }
    for (std::size_t i = 1; i < fds.size(); ++i) {
      if ((fds[i].revents & (POLLIN | POLLHUP)) == 0) {
        continue;
      }
      Managed& process = *owners[i];
      while (true) {
        const ssize_t n = read(process.output_fd, buffer, sizeof buffer);
        if (n > 0) {
          process.partial.append(buffer, static_cast<std::size_t>(n));
          print_lines(process, false);
          continue;
        }
        if (n == 0) {  // the process closed its output: it has ended
          print_lines(process, true);
          close(process.output_fd);
          process.output_fd = -1;
        }
        break;
      }
    }
  }

  void print_lines(Managed& process, bool flush_partial) {
    std::size_t start = 0;
    for (auto end = process.partial.find('\n'); end != std::string::npos;
         end = process.partial.find('\n', start)) {
      emit(process, process.partial.substr(start, end - start));
      start = end + 1;
    }
    process.partial.erase(0, start);
    if (flush_partial && !process.partial.empty()) {
      emit(process, process.partial);
      process.partial.clear();
    }
    // Whole lines out now, also into a pipe (`| tee`, a supervisor): a
    // process's progress must not wait for a 4 KiB buffer or the launch's end.
    out_ << std::flush;
  }

  void emit(Managed& process, const std::string& line) {
    out_ << "[" << process.spec->name << "] " << line << "\n";
    if (process.spec->hosts_components && line.rfind("wbi_host: running ", 0) == 0) {
      process.running = true;
    }
    for (std::size_t i = 0; i < deploy_.summaries.size(); ++i) {
      const auto& summary = deploy_.summaries[i];
      if (summary.process == process.spec->name && line.find(summary.match) != std::string::npos) {
        process.summary_lines.resize(deploy_.summaries.size());
        process.summary_lines[i] = line;
      }
    }
  }

  // Collects exits; returns true when the launch must stop, with `failed` set
  // when a required process failed.
  bool reap(bool& failed) {
    bool stop = false;
    for (auto& process : processes_) {
      if (process.pid <= 0) {
        continue;
      }
      int status = 0;
      if (waitpid(process.pid, &status, WNOHANG) != process.pid) {
        continue;
      }
      process.pid = -1;
      process.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      if (process.stopped_by_us) {
        say(process.spec->name + ": stopped");
        continue;
      }
      const bool ok = *process.exit_code == 0;
      say(process.spec->name +
          (ok ? ": exited" : ": failed with exit code " + std::to_string(*process.exit_code)));
      const bool will_respawn =
          process.spec->respawn.enabled && process.restarts < process.spec->respawn.max_retries;
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
  bool check_hangs(bool& failed) {
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
        say(process.spec->name + ": heartbeat heard; hung after " + std::to_string(timeout_s) +
            " s without one or without loop iterations");
      }
      if (!heard) {
        process.hang_reported = false;
        continue;
      }
      const auto timeout = seconds(timeout_s);
      std::string why;
      if (Clock::now() - *heard >= timeout) {
        const double silent_s = std::chrono::duration<double>(Clock::now() - *heard).count();
        why = "no status heartbeat from its components for " + std::to_string(silent_s) +
              " s (hang_timeout " + std::to_string(timeout_s) + " s): hung or stopped";
      } else if (const auto stalled =
                     heartbeats_->stalled_loop(process.spec->components, timeout)) {
        const double still_s =
            std::chrono::duration<double>(Clock::now() - stalled->advanced_at).count();
        why = "the loop of '" + stalled->instance + "' stopped at iteration " +
              std::to_string(stalled->iterations) + " " + std::to_string(still_s) +
              " s ago while its status goes on (hang_timeout " + std::to_string(timeout_s) +
              " s): deadlocked, or waiting for an input that stopped";
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

  bool supervise(Clock::time_point start) {
    bool failed = false;
    while (stop_signal == 0) {
      pump_output(std::chrono::milliseconds(50));
      if (reap(failed) || check_hangs(failed)) {
        return failed;
      }
      for (auto& process : processes_) {
        if (process.restart_at && Clock::now() >= *process.restart_at) {
          ++process.restarts;
          say(process.spec->name + ": respawn " + std::to_string(process.restarts) + " of " +
              std::to_string(process.spec->respawn.max_retries));
          if (!spawn(process) && process.spec->required) {
            return true;
          }
        }
      }
      const bool all_ended =
          std::all_of(processes_.begin(), processes_.end(),
                      [](const Managed& p) { return p.pid <= 0 && !p.restart_at; });
      if (all_ended) {
        say("every process has ended");
        return failed;
      }
      if (options_.duration_s > 0 && Clock::now() - start >= seconds(options_.duration_s)) {
        say("duration of " + std::to_string(options_.duration_s) + " s reached");
        return failed;
      }
    }
    say(std::string("interrupted (") + (stop_signal == SIGINT ? "SIGINT" : "SIGTERM") + ")");
    return failed;
  }

  // SIGTERM to every running process group, last started first; SIGKILL after the grace period.
  void stop_all() {
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
        say(process.spec->name + ": did not stop within " + std::to_string(options_.stop_grace_s) +
            " s: SIGKILL");
        kill(-process.pid, SIGKILL);
        int status = 0;
        waitpid(process.pid, &status, 0);
        process.exit_code = 128 + SIGKILL;
        process.pid = -1;
      }
    }
  }

  void drain_output() {
    while (std::any_of(processes_.begin(), processes_.end(),
                       [](const Managed& p) { return p.output_fd >= 0; })) {
      const auto before = std::count_if(processes_.begin(), processes_.end(),
                                        [](const Managed& p) { return p.output_fd >= 0; });
      pump_output(std::chrono::milliseconds(200));
      const auto after = std::count_if(processes_.begin(), processes_.end(),
                                       [](const Managed& p) { return p.output_fd >= 0; });
      if (after == before) {  // a grandchild may hold the pipe open: do not wait for it
        for (auto& p : processes_) {
          if (p.output_fd >= 0) {
            close(p.output_fd);
            p.output_fd = -1;
          }
        }
      }
    }
  }

  void print_summary() {
    say("summary:");
    for (const auto& process : processes_) {
      std::string state = !process.exit_code ? "not started"
                          : process.stopped_by_us
                              ? "stopped (exit code " + std::to_string(*process.exit_code) + ")"
                              : "exit code " + std::to_string(*process.exit_code);
      if (process.restarts > 0) {
        state += ", " + std::to_string(process.restarts) + " restart(s)";
      }
      out_ << "  " << process.spec->name << ": " << state << "\n";
    }
    for (std::size_t i = 0; i < deploy_.summaries.size(); ++i) {
      for (const auto& process : processes_) {
        if (i < process.summary_lines.size() && !process.summary_lines[i].empty()) {
          out_ << process.summary_lines[i] << "\n";
        }
      }
    }
    out_ << std::flush;
  }

  const DeployFile& deploy_;
  LaunchOptions options_;
  std::ostream& out_;
  std::vector<Managed> processes_;
  std::optional<dds::Participant> participant_;
  std::optional<Heartbeats> heartbeats_;  // when a process has a hang_timeout
};

}  // namespace

int run_launch(const DeployFile& deploy, const LaunchOptions& options, std::ostream& out) {
  if (pipe2(wake_pipe, O_CLOEXEC | O_NONBLOCK) != 0) {
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  stop_signal = 0;
  auto* previous_int = std::signal(SIGINT, on_stop_signal);
  auto* previous_term = std::signal(SIGTERM, on_stop_signal);
  int code = 1;
  try {
    code = Launcher(deploy, options, out).run();
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
