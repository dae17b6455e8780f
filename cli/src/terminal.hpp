// Terminal helpers for verbs that run for a while (`wbi record`, `wbi play`):
// a progress line, and single key presses without Enter.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include <termios.h>

namespace wbi::cli {

// On a terminal, one status line on stdout rewritten in place; otherwise
// (a pipe, a log file) one plain line per show().
class ProgressLine {
 public:
  ProgressLine();
  void show(const std::string& text);
  // Ends the in-place line so that what follows starts on a fresh line.
  void finish();
  bool on_terminal() const { return terminal_; }

 private:
  bool terminal_;
  bool open_ = false;
};

// Reads single key presses from stdin when it is a terminal and this process
// is in its foreground (raw mode, no echo); restores the terminal when
// destroyed. Inactive otherwise.
class Keyboard {
 public:
  Keyboard();
  ~Keyboard();
  Keyboard(const Keyboard&) = delete;
  Keyboard& operator=(const Keyboard&) = delete;

  bool active() const { return active_; }
  // The next key pressed within `timeout`, or nullopt (after waiting `timeout`
  // when inactive, so that a caller's loop keeps its pace).
  std::optional<char> poll(std::chrono::milliseconds timeout);

 private:
  bool active_ = false;
  termios saved_{};
};

// "12.3 MiB"
std::string human_bytes(double bytes);

}  // namespace wbi::cli
