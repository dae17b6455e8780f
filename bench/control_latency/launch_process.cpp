#include "launch_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

extern char** environ;

namespace wbi::bench {

namespace {

std::filesystem::path beside_this_executable(const std::string& program) {
  return std::filesystem::read_symlink("/proc/self/exe").parent_path() / program;
}

}  // namespace

LaunchProcess::LaunchProcess(const std::filesystem::path& deploy, double duration_s,
                             const std::filesystem::path& log)
    : LaunchProcess("wbi", {"launch", deploy.string(), "--duration", std::to_string(duration_s)},
                    log) {}

LaunchProcess::LaunchProcess(const std::string& program, const std::vector<std::string>& args,
                             const std::filesystem::path& log)
    : log_(log) {
  const std::string path = beside_this_executable(program).string();
  std::vector<std::string> words = {path};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& word : words) {
    argv.push_back(word.data());
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  const int failed = posix_spawn(&pid_, path.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (failed != 0) {
    pid_ = -1;
    throw std::runtime_error("cannot start " + path);
  }
}

LaunchProcess::~LaunchProcess() { stop(); }

bool LaunchProcess::wait(std::chrono::milliseconds timeout) {
  if (pid_ < 0) {
    return true;
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // polling a child's exit
  }
  return false;
}

void LaunchProcess::stop() {
  if (pid_ < 0) {
    return;
  }
  kill(pid_, SIGTERM);
  if (!wait(std::chrono::seconds(10))) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
}

std::string LaunchProcess::output() const {
  std::ifstream in(log_);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace wbi::bench
