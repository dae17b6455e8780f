// Verbs with sub-commands (`wbi topic list`, `wbi param set`, …): one
// dispatcher, so that each verb only lists its sub-commands. The usage lists
// them with their one-line help and ends with an example of each; no
// sub-command prints it and exits 1, --help prints it and exits 0, an unknown
// one is a UsageError naming the known ones.
#pragma once

#include <initializer_list>
#include <string>

#include "verb.hpp"

namespace wbi::cli {

struct Subcommand {
  const char* name;
  const char* help;     // one line
  const char* example;  // one command, e.g. "wbi topic list"
  int (*run)(Args args);
};

// notes: a paragraph after the sub-commands (what they share), or "".
int run_subcommand(const char* verb, Args args, std::initializer_list<Subcommand> subcommands,
                   const char* notes = "");

}  // namespace wbi::cli
