#include "terminal.hpp"

#include <poll.h>
#include <unistd.h>

#include <iomanip>
#include <iostream>
#include <iterator>
#include <sstream>

namespace wbi::cli {

ProgressLine::ProgressLine() : terminal_(isatty(STDOUT_FILENO) != 0) {}

void ProgressLine::show(const std::string& text) {
  if (terminal_) {
    std::cout << "\r\033[K" << text << std::flush;  // carriage return, clear to end of line
    open_ = true;
  } else {
    std::cout << text << std::endl;
  }
}

void ProgressLine::finish() {
  if (open_) {
    std::cout << "\n" << std::flush;
    open_ = false;
  }
}

Keyboard::Keyboard() {
  // Only in the foreground: a background process that changes the terminal's
  // mode is stopped by SIGTTOU (e.g. `wbi play FILE &`).
  if (isatty(STDIN_FILENO) == 0 || tcgetpgrp(STDIN_FILENO) != getpgrp() ||
      tcgetattr(STDIN_FILENO, &saved_) != 0) {
    return;
  }
  termios raw = saved_;
  raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);
  raw.c_cc[VMIN] = 1;
  raw.c_cc[VTIME] = 0;
  active_ = tcsetattr(STDIN_FILENO, TCSANOW, &raw) == 0;
}

Keyboard::~Keyboard() {
  if (active_) {
    tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
  }
}

std::optional<char> Keyboard::poll(std::chrono::milliseconds timeout) {
  if (!active_) {
    ::poll(nullptr, 0, static_cast<int>(timeout.count()));  // no keyboard: just the wait
    return std::nullopt;
  }
  pollfd input{STDIN_FILENO, POLLIN, 0};
  if (::poll(&input, 1, static_cast<int>(timeout.count())) <= 0) {
    return std::nullopt;
  }
  char key = 0;
  if (read(STDIN_FILENO, &key, 1) != 1) {
    return std::nullopt;
  }
  return key;
}

std::string human_bytes(double bytes) {
  static const char* const kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  std::size_t unit = 0;
  while (bytes >= 1024.0 && unit + 1 < std::size(kUnits)) {
    bytes /= 1024.0;
    ++unit;
  }
  std::ostringstream out;
  out << std::fixed << std::setprecision(unit == 0 ? 0 : 1) << bytes << ' ' << kUnits[unit];
  return out.str();
}

}  // namespace wbi::cli
