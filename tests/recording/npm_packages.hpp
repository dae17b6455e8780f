// The interop tests run independent readers and decoders from npm with node.
// Tests stay on loopback: scripts/install-deps fetches the packages
// (tests/npm-packages.txt) into wbi's npm cache, and this installs them from
// that cache with --offline into a scratch directory, or says why it could
// not (no node or npm on PATH, a package not in the cache), so that the test
// is skipped with that reason instead of failing.
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

// wbi's npm cache, where scripts/install-deps puts the packages.
inline std::filesystem::path npm_cache() {
  if (const char* cache = std::getenv("WBI_NPM_CACHE"); cache != nullptr && *cache != 0) {
    return cache;
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != 0) {
    return std::filesystem::path(xdg) / "wbi" / "npm";
  }
  const char* home = std::getenv("HOME");
  return std::filesystem::path(home != nullptr ? home : ".") / ".cache" / "wbi" / "npm";
}

// Installs `packages` (npm specs, e.g. "@mcap/core@^2", each listed in
// tests/npm-packages.txt) under `prefix`, from the cache only.
inline NodeWithPackages install_npm_packages(const std::filesystem::path& prefix,
                                             const std::vector<std::string>& packages) {
  const auto node = find_on_path("node");
  const auto npm = find_on_path("npm");
  if (!node || !npm) {
    return {{}, "node or npm not found on PATH"};
  }
  std::vector<std::string> args{"install",      "--offline", "--no-audit",         "--no-fund",
                                "--no-save",    "--cache",   npm_cache().string(), "--prefix",
                                prefix.string()};
  args.insert(args.end(), packages.begin(), packages.end());
  ChildProcess install(*npm, args,
                       {"npm_config_loglevel=error", "npm_config_update_notifier=false"});
  const auto code = install.wait(std::chrono::seconds(60));
  if (code != 0) {
    const std::string fix =
        " (scripts/install-deps fetches tests/npm-packages.txt into " + npm_cache().string() + ")";
    return {{},
            code ? "npm install --offline failed (exit " + std::to_string(*code) +
                       "): " + npm_error_line(install.output()) + fix
                 : "npm install --offline did not finish within 60 s" + fix};
  }
  return {*node, {}};
}

}  // namespace wbi::test
