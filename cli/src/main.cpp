// `wbi`: the one command-line entry point. Dispatches to the verb named by the
// first argument (see verb_table.cpp); with no verb it prints help.
#include <algorithm>
#include <csignal>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "verb.hpp"
#include "version.hpp"

namespace {

// The verbs by task, each with its help and, under it, an example: what a
// newcomer reads first, so it fits one screen (about 40 lines, 100 columns).
void print_help(std::ostream& out) {
  out << "usage: wbi [--help] [--version] VERB [ARGS...]\n\n"
         "wbi: the whole-body interface over DDS. Each verb's --help ends with examples.\n\n";
  std::optional<wbi::cli::Task> task;
  for (const auto& verb : wbi::cli::verbs()) {
    if (verb.task != task) {
      task = verb.task;
      out << wbi::cli::task_heading(verb.task) << "\n";
    }
    std::string name = verb.name;
    name.resize(std::max<std::size_t>(name.size() + 2, 12), ' ');
    out << "  " << name << verb.help << (verb.run == nullptr ? " [not built yet]" : "") << "\n"
        << "  " << std::string(name.size(), ' ') << verb.example << "\n";
  }
}

extern "C" void on_interrupt(int /*signal*/) {
  // Verbs that run until interrupted install their own handlers; this one ends
  // the others with the conventional code for SIGINT.
  std::_Exit(wbi::cli::kExitInterrupted);
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGINT, on_interrupt);
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    print_help(std::cout);
    return args.empty() ? wbi::cli::kExitError : wbi::cli::kExitOk;
  }
  if (args[0] == "--version") {
    std::cout << "wbi " << wbi::cli::kVersion << "\n";
    return wbi::cli::kExitOk;
  }
  for (const auto& verb : wbi::cli::verbs()) {
    if (args[0] != verb.name) {
      continue;
    }
    if (verb.run == nullptr) {
      std::cerr << "wbi " << verb.name << ": not built yet in this version of wbi\n";
      return wbi::cli::kExitError;
    }
    try {
      return verb.run(wbi::cli::Args(args).subspan(1));
    } catch (const wbi::cli::UsageError& e) {
      std::cerr << "wbi " << verb.name << ": " << e.what() << " (see 'wbi " << verb.name
                << " --help')\n";
    } catch (const std::exception& e) {
      std::cerr << "wbi " << verb.name << ": " << e.what() << "\n";
    }
    return wbi::cli::kExitError;
  }
  std::cerr << "wbi: unknown verb '" << args[0] << "' (see 'wbi --help')\n";
  return wbi::cli::kExitError;
}
