// A child process of the benchmark (`wbi launch FILE --duration S`, or any
// program beside it), its output going to a file (read after the run), stopped
// with SIGTERM (a launcher then stops its own processes).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace wbi::bench {

class LaunchProcess {
 public:
  // Starts `<dir of this executable>/wbi launch deploy --duration duration_s`.
  // Throws std::runtime_error when it cannot be started.
  LaunchProcess(const std::filesystem::path& deploy, double duration_s,
                const std::filesystem::path& log);
  // Starts `<dir of this executable>/program args...`.
  LaunchProcess(const std::string& program, const std::vector<std::string>& args,
                const std::filesystem::path& log);
  ~LaunchProcess();  // stop()
  LaunchProcess(const LaunchProcess&) = delete;
  LaunchProcess& operator=(const LaunchProcess&) = delete;

  // Waits up to `timeout` for the launcher to end by itself; true when it did.
  bool wait(std::chrono::milliseconds timeout);
  // SIGTERM, then SIGKILL after 10 s; returns once it has ended.
  void stop();
  // Everything it printed so far.
  std::string output() const;

 private:
  pid_t pid_ = -1;
  std::filesystem::path log_;
};

}  // namespace wbi::bench
