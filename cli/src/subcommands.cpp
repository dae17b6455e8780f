#include "subcommands.hpp"

#include <algorithm>
#include <iostream>

namespace wbi::cli {

int run_subcommand(const char* verb, Args args, std::initializer_list<Subcommand> subcommands) {
  std::string names, lines;
  for (const auto& subcommand : subcommands) {
    if (!names.empty()) {
      names += ",";
    }
    names += subcommand.name;
    std::string line = "  ";
    line += subcommand.name;
    line.resize(std::max<std::size_t>(line.size() + 2, 11), ' ');  // the helps in one column
    lines += line + subcommand.help + "\n";
  }
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::cout << "usage: wbi " << verb << " {" << names << "} [--help]\n\n" << lines;
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
