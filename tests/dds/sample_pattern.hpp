// The sensor samples the talker publishes: every value follows from the
// sequence number, so a receiver can check each one it gets.
#pragma once

#include <cstdint>
#include <string>

#include <wbi/msg/sensors.h>

namespace wbi::test {

inline constexpr std::size_t kTalkerJoints = 32;

inline double pattern_value(std::uint64_t seq, std::size_t joint) {
  return static_cast<double>(seq) + 0.001 * static_cast<double>(joint);
}

inline void fill_pattern(wbi::msg::SensorSample& sample, const std::string& robot,
                         std::uint64_t seq) {
  sample.header().robot(robot);
  sample.header().seq(seq);
  sample.header().stamp_ns(static_cast<std::int64_t>(seq) * 1'000'000);
  sample.encoder_position().resize(kTalkerJoints);
  for (std::size_t j = 0; j < kTalkerJoints; ++j) {
    sample.encoder_position()[j] = pattern_value(seq, j);
  }
}

// Empty when the sample matches the pattern of its sequence number; otherwise what differs.
inline std::string pattern_mismatch(const wbi::msg::SensorSample& sample,
                                    const std::string& robot) {
  if (sample.header().robot() != robot) {
    return "robot '" + sample.header().robot().to_string() + "'";
  }
  const auto seq = sample.header().seq();
  if (sample.header().stamp_ns() != static_cast<std::int64_t>(seq) * 1'000'000) {
    return "stamp of seq " + std::to_string(seq);
  }
  if (sample.encoder_position().size() != kTalkerJoints) {
    return "size " + std::to_string(sample.encoder_position().size());
  }
  for (std::size_t j = 0; j < kTalkerJoints; ++j) {
    if (sample.encoder_position()[j] != pattern_value(seq, j)) {
      return "joint " + std::to_string(j) + " of seq " + std::to_string(seq);
    }
  }
  return {};
}

}  // namespace wbi::test
