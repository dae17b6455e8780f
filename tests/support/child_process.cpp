#include "child_process.hpp"

#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace wbi::test {

namespace {

int decode_status(int status) {
  if (WIFEXITED(status)) {
    return WEXITSTATUS(status);
  }
  if (WIFSIGNALED(status)) {
    return 128 + WTERMSIG(status);
  }
  return -1;
}

std::filesystem::path unique_log_path() {
  static int counter = 0;
  return std::filesystem::temp_directory_path() /
         ("wbi_child_" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".log");
}

}  // namespace

ChildProcess::ChildProcess(const std::filesystem::path& program,
                           const std::vector<std::string>& args,
                           const std::vector<std::string>& env)
    : log_(unique_log_path()) {
  std::vector<std::string> argv_storage{program.string()};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& arg : argv_storage) {
    argv.push_back(arg.data());
  }
  argv.push_back(nullptr);

  std::vector<std::string> env_storage;
  for (char** e = environ; *e != nullptr; ++e) {
    env_storage.emplace_back(*e);
  }
  for (const auto& entry : env) {  // overrides replace inherited entries of the same key
    const auto key = entry.substr(0, entry.find('=') + 1);
    std::erase_if(env_storage, [&](const std::string& e) { return e.rfind(key, 0) == 0; });
    env_storage.push_back(entry);
  }
  std::vector<char*> envp;
  for (auto& entry : env_storage) {
    envp.push_back(entry.data());
  }
  envp.push_back(nullptr);

  // fork and exec rather than posix_spawn, for PR_SET_PDEATHSIG: a test that
  // crashes or that ctest kills at its timeout takes its children with it,
  // instead of leaving them on its DDS domain for the next run of the same
  // test. (The signal follows the forking thread: tests start children from
  // their main thread.) Until exec the child makes only async-signal-safe
  // calls; an exec failure comes back through a close-on-exec pipe.
  int exec_error_pipe[2];
  if (pipe2(exec_error_pipe, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("cannot start a child process: pipe: ") +
                             std::strerror(errno));
  }
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    close(exec_error_pipe[0]);
    int error = 0;
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent) {
      _exit(127);  // the parent is already gone
    }
    const int log = open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log < 0 || dup2(log, STDOUT_FILENO) < 0 || dup2(log, STDERR_FILENO) < 0) {
      error = errno;
    } else {
      close(STDIN_FILENO);
      execve(program.c_str(), argv.data(), envp.data());
      error = errno;
    }
    const ssize_t ignored = write(exec_error_pipe[1], &error, sizeof error);
    static_cast<void>(ignored);
    _exit(127);
  }
  const int fork_error = errno;
  close(exec_error_pipe[1]);
  if (pid_ < 0) {
    close(exec_error_pipe[0]);
    throw std::runtime_error("cannot start " + program.string() + ": " + std::strerror(fork_error));
  }
  int exec_error = 0;
  const ssize_t got = read(exec_error_pipe[0], &exec_error, sizeof exec_error);
  close(exec_error_pipe[0]);
  if (got == static_cast<ssize_t>(sizeof exec_error)) {
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
    throw std::runtime_error("cannot start " + program.string() + ": " + std::strerror(exec_error));
  }
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !exit_code_) {
    stop(SIGKILL, std::chrono::seconds(5));
  }
  std::error_code ignored;
  std::filesystem::remove(log_, ignored);
}

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout) {
  if (exit_code_) {
    return exit_code_;
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      exit_code_ = decode_status(status);
      return exit_code_;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      return std::nullopt;
    }
    // waitpid has no timeout; poll briefly (this waits for a process, not for a condition we could
    // observe).
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

int ChildProcess::stop(int signal_number, std::chrono::milliseconds grace) {
  if (exit_code_) {
    return *exit_code_;
  }
  kill(pid_, signal_number);
  if (auto code = wait(grace)) {
    return *code;
  }
  kill(pid_, SIGKILL);
  return wait(std::chrono::seconds(10)).value_or(-1);
}

bool ChildProcess::running() { return !wait(std::chrono::milliseconds(0)).has_value(); }

std::string ChildProcess::output() const {
  std::ifstream in(log_);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool ChildProcess::wait_for_output(const std::string& text, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (output().find(text) != std::string::npos) {
      return true;
    }
    if (!running()) {
      return output().find(text) != std::string::npos;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

}  // namespace wbi::test
