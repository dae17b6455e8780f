#include "subcommands.hpp"

#include <algorithm>
#include <iostream>
#include <vector>

#include "options.hpp"

namespace wbi::cli {

int run_subcommand(const char* verb, Args args, std::initializer_list<Subcommand> subcommands,
                   const char* notes) {
  std::string names, lines;
  std::vector<Example> examples;
  for (const auto& subcommand : subcommands) {
    if (!names.empty()) {
      names += ",";
    }
    names += subcommand.name;
    std::string line = "  ";
    line += subcommand.name;
    line.resize(std::max<std::size_t>(line.size() + 2, 11), ' ');  // the helps in one column
    lines += line + subcommand.help + "\n";
    examples.push_back({subcommand.example, ""});
  }
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::cout << "usage: wbi " << verb << " {" << names << "} [--help]\n\n" << lines;
    if (*notes != '\0') {
      std::cout << "\n" << notes;
    }
    std::cout << "\nEach has --help: wbi " << verb << " " << subcommands.begin()->name
              << " --help\n\n"
              << examples_text(examples);
    return args.empty() ? kExitError : kExitOk;
  }
  for (const auto& subcommand : subcommands) {
    if (args[0] == subcommand.name) {
      return subcommand.run(args.subspan(1));
    }
  }
  throw UsageError("unknown sub-command '" + args[0] + "' (" + names + ")");
}

}  // namespace wbi::cli
