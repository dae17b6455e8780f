// A robot name is taken once per domain: before a robot publishes anything it
// claims wbi/<robot>/description (a writer, no sample yet), lets discovery run
// for a window, and refuses to start when another live participant publishes
// that topic and claimed it first (the older participant wins; the same
// instant is broken by GUID prefix), so that of two robots started together
// exactly one runs. Ignored: participants of this very process, and those of a
// process of this host that no longer exists (a killed robot's, until its
// lease ends) — a respawned robot takes its own name back at once.
#pragma once

#include <memory>
#include <string>

#include <wbi/dds/participant.hpp>

namespace wbi::robot {

class RobotNameClaim {
 public:
  // Claims `robot` on the participant's domain, waiting window_s for discovery.
  // Throws std::runtime_error naming the robot and the other publisher (host,
  // pid, participant name) when the name is taken.
  RobotNameClaim(dds::Participant& participant, const std::string& robot, double window_s);
  ~RobotNameClaim();
  RobotNameClaim(const RobotNameClaim&) = delete;
  RobotNameClaim& operator=(const RobotNameClaim&) = delete;

 private:
  struct Writer;
  std::unique_ptr<Writer> writer_;  // the claim, seen by the others' discovery
};

}  // namespace wbi::robot
