#include "recorder_participant.hpp"

#include <fstream>
#include <iostream>
#include <string>

#include "../join_options.hpp"

namespace wbi::cli {

namespace {

// The kernel's cap on a socket's receive buffer; 0 when it cannot be read.
long receive_buffer_cap_bytes() {
  std::ifstream file("/proc/sys/net/core/rmem_max");
  long bytes = 0;
  return file >> bytes ? bytes : 0;
}

}  // namespace

dds::ParticipantOptions recorder_participant_options(const Options& options) {
  dds::ParticipantOptions participant = join_options(options, "wbi record", "observer");
  participant.udp_receive_buffer_bytes = kRecorderReceiveBufferBytes;
  return participant;
}

void warn_if_lost(const std::vector<recording::TopicLoss>& losses) {
  if (losses.empty()) {
    return;
  }
  std::uint64_t lost = 0;
  std::string topics;
  for (const auto& loss : losses) {
    lost += loss.samples;
    topics += (topics.empty() ? "" : ", ") + loss.topic + " " + std::to_string(loss.samples);
  }
  std::cerr << "warning: " << lost << " samples never reached the recorder (" << topics
            << "): they arrived while it could not take them in, and their writers no longer "
               "held them to send again (a writer keeps its last few samples, a stream's "
               "writer its newest one only)";
  const long cap = receive_buffer_cap_bytes();
  if (cap > 0 && cap < kRecorderReceiveBufferBytes) {
    std::cerr << "; the kernel caps its receive buffer at " << cap
              << " bytes (sudo sysctl -w net.core.rmem_max=" << kRecorderReceiveBufferBytes << ")";
  }
  std::cerr << "; a less loaded host helps too" << std::endl;
}

}  // namespace wbi::cli
