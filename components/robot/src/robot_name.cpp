#include "robot_name.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>

namespace wbi::robot {

namespace {

// Whether `other` claimed first: older, or (the same instant) the lower GUID
// prefix. A participant that does not announce its start (another vendor's
// or tool's) was there first.
bool claimed_first(const dds::ParticipantInfo& other, const dds::ParticipantInfo& self) {
  if (other.start_ns == 0 || other.start_ns != self.start_ns) {
    return other.start_ns < self.start_ns;
  }
  return other.guid_prefix < self.guid_prefix;
}

std::string describe(const dds::ParticipantInfo& other) {
  std::string text = other.name.empty() ? "a participant" : "participant '" + other.name + "'";
  if (!other.host.empty()) {
    text += " on host " + other.host;
  }
  if (other.pid > 0) {
    text += ", pid " + std::to_string(other.pid);
  }
  return text + " (GUID prefix " + other.guid_prefix + ")";
}

}  // namespace

struct RobotNameClaim::Writer {
  Writer(dds::Participant& participant, const std::string& topic)
      : publisher(participant, topic, dds::qos::kLatched) {}
  dds::Publisher<wbi::msg::RobotDescription> publisher;
};

RobotNameClaim::RobotNameClaim(dds::Participant& participant, const std::string& robot,
                               double window_s) {
  const std::string topic = dds::topics::description(robot);
  writer_ = std::make_unique<Writer>(participant, topic);
  if (window_s <= 0.0) {
    return;
  }
  // Discovery has no "complete" event: the window is what a peer needs to
  // announce itself (250 ms announcement period, dds/src/participant.cpp).
  std::this_thread::sleep_for(std::chrono::duration<double>(window_s));
  const auto& self = participant.info();
  for (const auto& other : participant.publishers_of(topic)) {
    // Fast DDS's GUID prefix: vendor, host and process (8 bytes), then the
    // participant: the first 16 hex digits equal means this very process
    // (its own endpoints are reported by discovery too).
    const bool this_process = other.guid_prefix.compare(0, 16, self.guid_prefix, 0, 16) == 0;
    if (this_process || participant.has_ended(other) || !claimed_first(other, self)) {
      continue;
    }
    throw std::runtime_error("robot '" + robot + "' is already running on DDS domain " +
                             std::to_string(participant.domain_id()) + ": " + topic +
                             " is published by " + describe(other) +
                             "; run this one under another robot name or on another domain");
  }
}

RobotNameClaim::~RobotNameClaim() = default;

}  // namespace wbi::robot
