#include "joint_claim.hpp"

#include <cstdio>
#include <thread>

#include <wbi/dds/topics.hpp>
#include <wbi/types.hpp>

namespace wbi::proxy {

JointClaim::JointClaim(dds::Participant& participant, std::string robot, std::string controller,
                       std::vector<std::string> joints, std::vector<int> robot_indices)
    : robot_(std::move(robot)),
      controller_(std::move(controller)),
      joints_(std::move(joints)),
      robot_indices_(std::move(robot_indices)),
      client_(participant, dds::topics::claim_service(robot_)),
      participant_(std::string(client_.client_id()).substr(0, 24)),
      owners_(participant, dds::topics::joint_owners(robot_), dds::qos::kLatched,
              [this](const wbi::msg::JointOwners& owners, const dds::detail::SampleInfo&) {
                on_owners(owners);
              }) {}

JointClaim::~JointClaim() { release(); }

wbi::msg::JointClaimReply JointClaim::request(wbi::msg::ClaimAction action,
                                              std::chrono::nanoseconds timeout, bool force) {
  wbi::msg::JointClaimRequest request;
  request.robot(robot_);
  request.controller(controller_);
  request.action(action);
  request.force(force);
  if (action == wbi::msg::ClaimAction::CLAIM) {
    for (const auto& joint : joints_) {
      request.joints().push_back(joint);
    }
  }
  wbi::msg::JointClaimReply reply;
  if (client_.try_call(request, reply, timeout) != dds::CallStatus::ok) {
    throw TimeoutError("robot '" + robot_ + "' answered no joint claim of '" + controller_ +
                       "' on " + client_.service() + " within " +
                       std::to_string(std::chrono::duration<double>(timeout).count()) +
                       " s: is its actuator side running?");
  }
  return reply;
}

void JointClaim::claim(std::chrono::nanoseconds timeout, bool force) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  standing_ = Standing::unknown;
  const auto reply = request(wbi::msg::ClaimAction::CLAIM, timeout, force);
  if (reply.error().size() > 0) {
    throw Error("robot '" + robot_ + "': " + std::string(reply.error().c_str()));
  }
  claimed_ = true;
  while (standing_.load() != Standing::held) {
    if (std::chrono::steady_clock::now() > deadline) {
      throw TimeoutError("robot '" + robot_ + "' granted the claim of '" + controller_ +
                         "' but its owners topic " + dds::topics::joint_owners(robot_) +
                         " did not show it in time");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void JointClaim::on_owners(const wbi::msg::JointOwners& owners) {
  Standing standing = Standing::held;
  for (std::size_t k = 0; k < joints_.size(); ++k) {
    const auto joint = static_cast<std::size_t>(robot_indices_[k]);
    if (joint >= owners.controllers().size() || joint >= owners.participants().size()) {
      return;  // not this robot's description: the proxy's own checks name it
    }
    const auto& controller = owners.controllers()[joint];
    if (controller.size() == 0) {
      standing = Standing::free;
    } else if (controller_ != controller.c_str() ||
               participant_ != owners.participants()[joint].c_str()) {
      std::lock_guard lock(taken_mutex_);
      taken_ = "joint '" + joints_[k] + "' is held by '" + controller.c_str() + "'";
      standing_ = Standing::taken;
      return;
    }
  }
  standing_ = standing;
}

void JointClaim::check() {
  switch (standing_.load()) {
    case Standing::unknown:
    case Standing::held:
      return;
    case Standing::taken: {
      std::lock_guard lock(taken_mutex_);
      throw Error("robot '" + robot_ + "': " + taken_ + " (claimed with force): controller '" +
                  controller_ + "' no longer commands it");
    }
    case Standing::free:
      // The robot holds no claim of ours: it restarted (a released claim ends
      // with close()). Claim again before commanding.
      // One call: the controller's other threads print too (runtime/console_line.hpp).
      std::fprintf(stderr,
                   "[%s] robot '%s' shows our joints unclaimed (restarted?): claiming them again\n",
                   controller_.c_str(), robot_.c_str());
      claim(std::chrono::seconds(1));
      return;
  }
}

void JointClaim::release() noexcept {
  if (!claimed_.exchange(false) || !client_.connected()) {
    return;  // a robot that is gone ends the claim when this participant leaves
  }
  try {
    request(wbi::msg::ClaimAction::RELEASE, std::chrono::milliseconds(200), false);
  } catch (const std::exception&) {
    // The robot is gone or silent: its claim ends when this participant leaves.
  }
}

}  // namespace wbi::proxy
