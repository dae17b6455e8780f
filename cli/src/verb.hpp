// A verb of the `wbi` command line: one file per verb in verbs/, registered in
// verb_table.cpp. The verb's run() gets the arguments after its name and
// returns the process exit code; errors are thrown (see main.cpp). `wbi --help`
// lists the verbs by the task they serve, each with its help and an example.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace wbi::cli {

using Args = std::span<const std::string>;

// The tasks `wbi --help` groups the verbs by, in its order.
enum class Task { run, watch, control, record, model, robot };

// "run: start a deployment", the heading of a task's verbs.
const char* task_heading(Task task);

struct Verb {
  const char* name;
  Task task;
  const char* help;     // one line, shown by `wbi --help`
  const char* example;  // one command, shown by `wbi --help` under the help
  int (*run)(Args args);
};

// The command line was wrong: main() prints the message and a hint to --help, exit 1.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every verb, in the order `wbi --help` lists them (by task).
std::span<const Verb> verbs();

// Exit codes shared by all verbs.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;
inline constexpr int kExitInterrupted = 130;

}  // namespace wbi::cli
