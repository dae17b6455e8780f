// The files of a windowed recorder: their names (time and trigger kind), the
// ".part" name a file has while it is written (renamed when complete, so a
// name ending in .mcap is always a whole file) and the --max-files policy:
// the oldest file this recorder wrote is deleted before one too many would
// be started. Files it did not write are never touched.
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <string>

#include <wbi/vocabulary/event.hpp>

namespace wbi::recording {

class WindowFiles {
 public:
  // Creates the directory (std::runtime_error naming it when that fails).
  // max_files 0: no limit.
  WindowFiles(std::filesystem::path directory, std::size_t max_files,
              std::function<void(const std::string&)> log);

  // The final path of a new file for a trigger (a "_2", "_3", ... suffix when
  // that name is taken), after deleting the oldest kept file if the limit
  // would be passed.
  std::filesystem::path start(std::uint64_t stamp_ns, EventKind kind);
  // Where the file is written until finish().
  static std::filesystem::path part_path(const std::filesystem::path& final_path);
  // Renames the written file to its final name and keeps it.
  void finish(const std::filesystem::path& final_path);

  const std::deque<std::filesystem::path>& kept() const { return kept_; }
  std::size_t deleted() const { return deleted_; }

 private:
  std::filesystem::path directory_;
  std::size_t max_files_;
  std::function<void(const std::string&)> log_;
  std::deque<std::filesystem::path> kept_;  // oldest first
  std::size_t deleted_ = 0;
};

}  // namespace wbi::recording
