// Samples of one topic that never reached its recorder's reader: what
// Recorder::losses() and WindowRecorder::losses() report.
#pragma once

#include <cstdint>
#include <string>

namespace wbi::recording {

struct TopicLoss {
  std::string topic;
  std::uint64_t samples = 0;
};

}  // namespace wbi::recording
