// The times of a controller's progress lines ("[controller] t =  10.00 s  …")
// in a launch's output: tests check that the run got there, not the exact
// text of one line (a controller on its own timer prints "t =   1.01" under load).
#pragma once

#include <regex>
#include <string>
#include <vector>

namespace wbi::test {

inline std::vector<double> progress_times(const std::string& output,
                                          const std::string& process = "controller") {
  const std::regex line("\\[" + process + "\\] t = +([0-9]+\\.[0-9]+) s");
  std::vector<double> times;
  for (auto it = std::sregex_iterator(output.begin(), output.end(), line);
       it != std::sregex_iterator(); ++it) {
    times.push_back(std::stod((*it)[1].str()));
  }
  return times;
}

}  // namespace wbi::test
