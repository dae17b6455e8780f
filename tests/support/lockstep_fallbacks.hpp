#pragma once
// The wall-clock fallbacks a lockstep run reached, read from its launch's
// output (the same lines as scripts/repro-check's FALLBACKS; deploy/README.md,
// "Reproducible lockstep"). A run that reached one is no longer the
// experiment: on a machine busy enough that a process waits seconds for a
// core, its figures may differ in the last digit, and it says so.
#include <regex>
#include <string>
#include <vector>

namespace wbi::test {

inline std::vector<std::string> lockstep_fallbacks(const std::string& launch_output) {
  static const std::vector<std::pair<std::string, std::regex>> kFallbacks = {
      {"robot stepped without a command", std::regex("not answered by every controller")},
      {"estimate without its inputs", std::regex("estimated without all its inputs")},
      {"reference late", std::regex("[1-9][0-9]* points late")},
      {"process hung", std::regex("hung or stopped")},
  };
  std::vector<std::string> reached;
  for (const auto& [name, pattern] : kFallbacks) {
    if (std::regex_search(launch_output, pattern)) {
      reached.push_back(name);
    }
  }
  return reached;
}

}  // namespace wbi::test
