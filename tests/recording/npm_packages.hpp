// The interop tests run independent readers and decoders from the npm
// registry with node: this installs them into a scratch directory, or says
// why it could not (no node or npm on PATH, npm failed or took too long), so
// that the test is skipped with that reason instead of failing.
#pragma once

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "child_process.hpp"

namespace wbi::test {

inline std::optional<std::filesystem::path> find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) {
    return std::nullopt;
  }
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const auto candidate = std::filesystem::path(dir.empty() ? "." : dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  return std::nullopt;
}

// The line of npm's output that says what went wrong (else its last line).
inline std::string npm_error_line(const std::string& text) {
  std::string line;
  std::string last;
  std::stringstream lines(text);
  while (std::getline(lines, line)) {
    if (line.find("error") != std::string::npos && line.find("complete log") == std::string::npos) {
      return line;
    }
    if (!line.empty()) {
      last = line;
    }
  }
  return last;
}

struct NodeWithPackages {
  std::filesystem::path node;  // empty when skipped
  std::string skip_reason;     // empty when installed
};

// Installs `packages` (npm specs, e.g. "@mcap/core@^2") under `prefix`.
inline NodeWithPackages install_npm_packages(const std::filesystem::path& prefix,
                                             const std::vector<std::string>& packages) {
  const auto node = find_on_path("node");
  const auto npm = find_on_path("npm");
  if (!node || !npm) {
    return {{}, "node or npm not found on PATH"};
  }
  std::vector<std::string> args{"install",   "--no-audit", "--no-fund",
                                "--no-save", "--prefix",   prefix.string()};
  args.insert(args.end(), packages.begin(), packages.end());
  ChildProcess install(*npm, args,
                       {"npm_config_loglevel=error", "npm_config_update_notifier=false"});
  const auto code = install.wait(std::chrono::seconds(90));
  if (code != 0) {
    return {{},
            code ? "npm install failed (exit " + std::to_string(*code) +
                       "): " + npm_error_line(install.output())
                 : "npm install did not finish within 90 s"};
  }
  return {*node, {}};
}

}  // namespace wbi::test
