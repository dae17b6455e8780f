// The robot's side of joint claims on DDS (idl/claims.idl): answers
// wbi/<robot>/claims, publishes wbi/<robot>/claims/owners after every change,
// and says every change in one line. The rules are JointClaims'; the lock
// that guards them is the actuator side's (commands check claims under it).
//
//   claims: 'pd' (participant 0f1e…, pid 4242 on host h) holds joint_1, joint_2
//   claims: 'supervisor' (…) took joint_1 from 'pd' by force
//   claims: 'pd' released joint_1, joint_2
//
// Each change is also an event on wbi/events, naming the joints: CLAIM_CHANGED
// (info) for a claim granted or released, or for joints whose owner's claim
// had ended; CLAIM_FORCED (warning) for joints taken from their owner by force.
//
// Counters on the owner's status: claims_granted, claims_refused. A refused
// claim is one line per kind and sender (RejectionLog): a client that retries
// cannot flood the log.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <wbi/msg/claims.h>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/server.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/status_report.hpp>

#include "joint_claims.hpp"
#include "rejection_log.hpp"

namespace wbi::robot {

class ClaimDesk {
 public:
  // `claims` and `lock` outlive the desk; `now_ns` is the loop time (when claims lapse).
  ClaimDesk(dds::Participant& participant, const std::string& robot, JointClaims& claims,
            std::mutex& lock, const std::atomic<std::int64_t>& now_ns,
            runtime::StatusReport& report, runtime::EventLog& events, RejectionLog& rejections);
  ~ClaimDesk();  // stops answering first
  ClaimDesk(const ClaimDesk&) = delete;
  ClaimDesk& operator=(const ClaimDesk&) = delete;

  // What the service calls (a DDS or worker thread); public for tests.
  void answer(const wbi::msg::JointClaimRequest& request, wbi::msg::JointClaimReply& reply);

 private:
  // The joint indices of `request.joints()`, or an error naming an unknown one.
  std::string resolve(const wbi::msg::JointClaimRequest& request, std::vector<int>& joints) const;
  // Who `claimant` is, for log lines: its name, participant, process and host.
  std::string describe(const Claimant& claimant) const;
  // Says a granted claim: a line per change, an event per kind of change.
  void say_granted(const Claimant& who, const std::vector<int>& joints,
                   const JointClaims::Outcome& outcome, bool force);
  // Publishes the owners as they are now (call without holding lock_).
  void publish_owners();

  dds::Participant& participant_;
  const std::string robot_;
  JointClaims& claims_;
  std::mutex& lock_;
  const std::atomic<std::int64_t>& now_ns_;
  runtime::StatusReport& report_;
  runtime::EventLog& events_;
  RejectionLog& rejections_;
  runtime::StatusCounter& granted_;
  runtime::StatusCounter& refused_;
  std::mutex publish_mutex_;  // one owners sample at a time, in generation order
  dds::Publisher<wbi::msg::JointOwners> owners_;
  std::unique_ptr<dds::Server<wbi::msg::JointClaimRequest, wbi::msg::JointClaimReply>> server_;
};

}  // namespace wbi::robot
