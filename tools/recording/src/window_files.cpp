#include "window_files.hpp"

#include <ctime>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <wbi/recording/window_recorder.hpp>

namespace wbi::recording {

std::string window_file_name(std::uint64_t stamp_ns, EventKind kind) {
  const auto seconds = static_cast<std::time_t>(stamp_ns / 1'000'000'000u);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  std::ostringstream name;
  name << std::put_time(&utc, "%Y%m%d-%H%M%S") << '.' << std::setw(3) << std::setfill('0')
       << stamp_ns % 1'000'000'000u / 1'000'000u << '_' << to_string(kind) << ".mcap";
  return name.str();
}

WindowFiles::WindowFiles(std::filesystem::path directory, std::size_t max_files,
                         std::function<void(const std::string&)> log)
    : directory_(std::move(directory)), max_files_(max_files), log_(std::move(log)) {
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error || !std::filesystem::is_directory(directory_)) {
    throw std::runtime_error(directory_.string() + ": cannot create the directory" +
                             (error ? " (" + error.message() + ")" : std::string()));
  }
}

std::filesystem::path WindowFiles::part_path(const std::filesystem::path& final_path) {
  return final_path.string() + ".part";
}

std::filesystem::path WindowFiles::start(std::uint64_t stamp_ns, EventKind kind) {
  while (max_files_ > 0 && kept_.size() >= max_files_) {
    std::error_code error;
    std::filesystem::remove(kept_.front(), error);
    if (log_) {
      log_("window: deleted " + kept_.front().string() + " (--max-files " +
           std::to_string(max_files_) + ")" + (error ? ": " + error.message() : std::string()));
    }
    kept_.pop_front();
    ++deleted_;
  }
  const std::string name = window_file_name(stamp_ns, kind);
  std::filesystem::path path = directory_ / name;
  const std::string stem = path.stem().string();
  for (int n = 2; std::filesystem::exists(path) || std::filesystem::exists(part_path(path)); ++n) {
    path = directory_ / (stem + "_" + std::to_string(n) + ".mcap");
  }
  return path;
}

void WindowFiles::finish(const std::filesystem::path& final_path) {
  std::filesystem::rename(part_path(final_path), final_path);  // throws naming both paths
  kept_.push_back(final_path);
}

}  // namespace wbi::recording
