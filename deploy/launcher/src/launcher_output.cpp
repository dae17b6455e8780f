// The launched processes' output: read from their pipes, printed line by line
// prefixed with the process's name, the summary lines kept, and the closing summary.
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <string>
#include <vector>

#include "launcher_impl.hpp"

namespace wbi::launch {

namespace detail {

// Reads what the processes printed, for up to `timeout`, and prints it line by line.
void Launcher::pump_output(std::chrono::milliseconds timeout) {
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

void Launcher::print_lines(Managed& process, bool flush_partial) {
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

void Launcher::emit(Managed& process, const std::string& line) {
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

void Launcher::drain_output() {
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

void Launcher::print_summary() {
  say("summary:");
  for (const auto& process : processes_) {
    std::string state = !process.exit_code ? "not started"
                        : process.stopped_by_us
                            ? "stopped (exit code " + std::to_string(*process.exit_code) + ")"
                            : "exit code " + std::to_string(*process.exit_code);
    if (process.restarts > 0) {
      state += ", " + std::to_string(process.restarts) + " restart(s)";
    }
    if (process.start_retries > 0) {
      state +=
          ", started again after " + std::to_string(process.start_retries) + " stalled start(s)";
    }
    if (!process.failure.empty()) {
      state += ": FAILED, " + process.failure;
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

}  // namespace detail

}  // namespace wbi::launch
