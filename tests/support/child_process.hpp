// A child process for multi-process tests: started with posix_spawn, its
// stdout and stderr captured to a file, stopped (SIGTERM, then SIGKILL) when
// the object goes away, so no test leaves a process behind.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <sys/types.h>

namespace wbi::test {

class ChildProcess {
 public:
  // program: a path; args: without argv[0]. env: extra "KEY=VALUE" entries
  // added to this process's environment. Throws std::runtime_error when the
  // process cannot be started.
  ChildProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
               const std::vector<std::string>& env = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }

  // Waits for the process to exit; returns its exit code (128 + signal when
  // killed by a signal), or nullopt on timeout.
  std::optional<int> wait(std::chrono::milliseconds timeout);

  // Sends a signal (SIGTERM by default) and waits up to `grace` for the exit;
  // SIGKILL after that. Returns the exit code.
  int stop(int signal_number = 15, std::chrono::milliseconds grace = std::chrono::seconds(5));

  bool running();

  // Everything the process printed so far (stdout and stderr interleaved).
  std::string output() const;

  // Polls output() until it contains `text`; false on timeout or exit.
  bool wait_for_output(const std::string& text, std::chrono::milliseconds timeout);

 private:
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
  std::filesystem::path log_;
};

}  // namespace wbi::test
