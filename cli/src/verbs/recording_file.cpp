#include "recording_file.hpp"

#include <ctime>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace wbi::cli {

namespace {
constexpr double kNsPerSecond = 1e9;
}  // namespace

void require_readable_recording(const std::string& file, const mcap::FileInfo& info) {
  if (info.file_size == 0) {
    throw std::runtime_error(file + ": empty file (0 bytes), not an MCAP recording");
  }
  if (info.truncated && info.truncation.readable_bytes == 0) {
    throw std::runtime_error(file + ": " + info.truncation.description);
  }
}

std::string utc_time(std::uint64_t ns) {
  const auto seconds = static_cast<std::time_t>(ns / 1'000'000'000u);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  std::ostringstream out;
  out << std::put_time(&utc, "%Y-%m-%d %H:%M:%S") << '.' << std::setw(9) << std::setfill('0')
      << ns % 1'000'000'000u << " UTC";
  return out.str();
}

std::string truncation_line(const std::string& file, const mcap::FileInfo& info) {
  const auto& cut = info.truncation;
  std::ostringstream line;
  line << file << ": " << cut.description;
  if (!cut.cut_record.empty()) {
    const std::uint64_t record_end = cut.cut_record_offset + cut.cut_record_bytes;
    line << "; lost: its last " << record_end - info.file_size << " bytes";
    if (cut.lost_times_known) {
      line << std::fixed << std::setprecision(3) << ", so all its messages, logged from "
           << utc_time(cut.lost_start_time) << " to " << utc_time(cut.lost_end_time) << " ("
           << static_cast<double>(cut.lost_end_time - cut.lost_start_time) / kNsPerSecond << " s)";
    }
    line << ", and whatever was recorded after it";
  }
  line << "; readable: " << info.statistics.message_count << " messages in " << cut.readable_bytes
       << " bytes (above)";
  return line.str();
}

}  // namespace wbi::cli
