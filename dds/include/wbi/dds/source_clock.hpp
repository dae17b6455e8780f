// The clock of DDS source timestamps (SampleInfo::source_stamp_ns): the system
// clock, in ns since the Unix epoch. A time read here compares with a sample's
// source stamp on the same host, or across hosts whose clocks are synchronised.
#pragma once

#include <chrono>
#include <cstdint>

namespace wbi::dds {

inline std::int64_t source_clock_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace wbi::dds
