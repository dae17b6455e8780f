// What both modes of `wbi record` (whole run, windows) share about joining:
// the participant they record through, and what they say when DDS lost
// samples before they reached it.
#pragma once

#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/recording/topic_loss.hpp>

#include "../options.hpp"

namespace wbi::cli {

// A recorder's process may be descheduled for a while on a busy host; every
// datagram that arrives meanwhile waits in its socket's receive buffer, and a
// stream's writer keeps only its newest sample to send again. Stopped for
// 0.5 s in test_multihost_tools_secure, a recorder with the OS default
// (208 KiB) lost 44 of 3000 sensor samples, with 4 MiB none. The kernel caps
// it at net.core.rmem_max.
inline constexpr int kRecorderReceiveBufferBytes = 4 << 20;

// join_options() as the observer, with kRecorderReceiveBufferBytes.
dds::ParticipantOptions recorder_participant_options(const Options& options);

// On stderr, when a topic lost any: how many samples never reached the
// recorder, of which topics, why, and what helps (a larger
// net.core.rmem_max, a less loaded host).
void warn_if_lost(const std::vector<recording::TopicLoss>& losses);

}  // namespace wbi::cli
