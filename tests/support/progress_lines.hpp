// The times of a controller's progress lines ("[controller] t =  10.00 s  …")
// in a launch's output: tests check that the run got there, not the exact
// text of one line (a controller on its own timer prints "t =   1.01" under load).
// And the number a run ends with ("final max joint error: 0.0006 rad").
#pragma once

#include <optional>
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

// The number after the last `marker` in `output` ("final max joint error: "),
// none when the marker is missing.
inline std::optional<double> last_value_after(const std::string& output,
                                              const std::string& marker) {
  const auto at = output.rfind(marker);
  if (at == std::string::npos) {
    return std::nullopt;
  }
  return std::stod(output.substr(at + marker.size()));
}

}  // namespace wbi::test
