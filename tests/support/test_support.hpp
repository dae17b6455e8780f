// Paths and DDS domain ids for tests.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace wbi::test {

// The source tree, from WBI_SOURCE_DIR (set by ctest for every test).
inline std::filesystem::path source_dir() {
  const char* dir = std::getenv("WBI_SOURCE_DIR");
  return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::current_path();
}

// The build tree, from WBI_BINARY_DIR (set by ctest for every test).
inline std::filesystem::path binary_dir() {
  const char* dir = std::getenv("WBI_BINARY_DIR");
  return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::current_path();
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

inline constexpr const char* kSharedMissing = "skipped: ../shared not found";

}  // namespace wbi::test
