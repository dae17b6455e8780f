// Starting one process of a deploy file: finding its program, and spawning it
// in its own process group with its output on a pipe.
#include <fcntl.h>
#include <spawn.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "launcher_impl.hpp"

namespace wbi::launch {

namespace {

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

}  // namespace

namespace detail {

bool Launcher::spawn(Managed& process) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    const std::string why = std::string("cannot create a pipe: ") + std::strerror(errno);
    say(process.spec->name + ": " + why);
    tell(EventSeverity::error, EventKind::process_exited, process, "not started: " + why);
    return false;
  }
  std::string program;
  try {
    program = resolve_program(process.spec->command.front());
  } catch (const std::exception& e) {
    say(process.spec->name + ": " + e.what());
    tell(EventSeverity::error, EventKind::process_exited, process,
         std::string("not started: ") + e.what());
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
    const std::string why = "cannot start " + program + ": " + std::strerror(rc);
    say(process.spec->name + ": " + why);
    tell(EventSeverity::error, EventKind::process_exited, process, "not started: " + why);
    return false;
  }
  fcntl(fds[0], F_SETFL, O_NONBLOCK);
  process.output_fd = fds[0];
  process.exit_code.reset();
  process.restart_at.reset();
  process.hang_reported = false;
  process.heard = false;
  process.running = false;
  process.failure.clear();  // judged by this run
  if (heartbeats_) {
    heartbeats_->forget(process.spec->components);  // the new ones are not late yet
  }
  const std::string started = "started (pid " + std::to_string(process.pid) + ")";
  say(process.spec->name + ": " + started);
  tell(EventSeverity::info, EventKind::process_started, process, started);
  return true;
}

}  // namespace detail

}  // namespace wbi::launch
