// The proxy's claim on its controlled joints (idl/claims.idl,
// components/robot/src/joint_claims.hpp for the robot's rules):
//   claim()    at init(): granted, or wbi::Error naming each contested joint
//              and its owner, before any command is sent;
//   check()    before every command: nothing to do (and no allocation) while
//              the robot's owners topic shows the joints as this proxy's; a
//              wbi::Error once another controller took one (a forced claim);
//              a claim again when the robot shows them free (a restarted robot);
//   release()  at close() and destruction.
// The claimant is this proxy's participant (the one its commands are written
// from) under DdsInterfaceOptions::controller.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include <wbi/msg/claims.h>
#include <wbi/dds/client.hpp>
#include <wbi/dds/subscriber.hpp>

namespace wbi::proxy {

class JointClaim {
 public:
  // `joints`: the controlled joints' names and their indices in the robot's description.
  JointClaim(dds::Participant& participant, std::string robot, std::string controller,
             std::vector<std::string> joints, std::vector<int> robot_indices);
  ~JointClaim();  // releases, bounded
  JointClaim(const JointClaim&) = delete;
  JointClaim& operator=(const JointClaim&) = delete;

  // Returns once the robot granted the claim and its owners topic shows it:
  // from then on, every owners sample is newer than the claim (one writer's
  // samples arrive in order), so a late copy of an older one cannot read as
  // a takeover.
  void claim(std::chrono::nanoseconds timeout, bool force = false);
  void check();
  void release() noexcept;

 private:
  enum class Standing { unknown, held, free, taken };
  void on_owners(const wbi::msg::JointOwners& owners);
  wbi::msg::JointClaimReply request(wbi::msg::ClaimAction action, std::chrono::nanoseconds timeout,
                                    bool force);

  const std::string robot_;
  const std::string controller_;
  const std::vector<std::string> joints_;
  const std::vector<int> robot_indices_;
  dds::Client<wbi::msg::JointClaimRequest, wbi::msg::JointClaimReply> client_;
  const std::string participant_;  // this proxy's GUID prefix (24 hex digits)
  std::atomic<Standing> standing_{Standing::unknown};
  std::atomic<bool> claimed_{false};
  std::mutex taken_mutex_;
  std::string taken_;  // "joint 'b' is held by 'supervisor'", when standing_ is taken
  dds::Subscriber<wbi::msg::JointOwners> owners_;
};

}  // namespace wbi::proxy
