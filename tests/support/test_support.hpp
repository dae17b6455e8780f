// Paths, DDS domain ids and bounded waits for tests.
#pragma once

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>

namespace wbi::test {

// The source tree: WBI_SOURCE_DIR (set by ctest for every test), else the
// one this test was built from (so a test binary also runs by hand).
inline std::filesystem::path source_dir() {
  const char* dir = std::getenv("WBI_SOURCE_DIR");
  return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::path(WBI_BUILT_SOURCE_DIR);
}

// The build tree: WBI_BINARY_DIR (set by ctest), else the one this test was built in.
inline std::filesystem::path binary_dir() {
  const char* dir = std::getenv("WBI_BINARY_DIR");
  return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::path(WBI_BUILT_BINARY_DIR);
}

// A URDF the project ships, e.g. project_model("arm7.urdf").
inline std::filesystem::path project_model(const std::string& file) {
  return source_dir() / "models" / file;
}

// ../shared/models beside the source tree, when it exists. Tests that need it
// call GTEST_SKIP() << kSharedMissing otherwise.
inline std::optional<std::filesystem::path> shared_models_dir() {
  const auto dir = source_dir().parent_path() / "shared" / "models";
  if (std::filesystem::is_directory(dir)) {
    return dir;
  }
  return std::nullopt;
}

inline constexpr const char* kSharedMissing = "../shared not found";

// Polls `condition` every millisecond until it holds (true) or `timeout`
// passes (false): a bounded wait on a condition, not a sleep.
template <class Condition>
bool eventually(Condition condition, std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace wbi::test
