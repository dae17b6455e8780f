#include "claim_desk.hpp"

#include <string>

#include <wbi/dds/topics.hpp>
#include <wbi/runtime/console_line.hpp>

namespace wbi::robot {

namespace {

std::string joint_list(const JointClaims& claims, const std::vector<int>& joints) {
  std::string text;
  for (const int joint : joints) {
    if (!text.empty()) {
      text += ", ";
    }
    text += claims.joint_name(joint);
  }
  return text;
}

// The joints as an event's subject: "joint_1,joint_2".
std::string joint_subject(const JointClaims& claims, const std::vector<int>& joints) {
  std::string text;
  for (const int joint : joints) {
    text.append(text.empty() ? "" : ",").append(claims.joint_name(joint));
  }
  return text;
}

dds::detail::Guid participant_guid(const Claimant& claimant) {
  dds::detail::Guid guid{};
  std::copy(claimant.participant.begin(), claimant.participant.end(), guid.begin());
  return guid;
}

}  // namespace

ClaimDesk::ClaimDesk(dds::Participant& participant, const std::string& robot, JointClaims& claims,
                     std::mutex& lock, const std::atomic<std::int64_t>& now_ns,
                     runtime::StatusReport& report, runtime::EventLog& events,
                     RejectionLog& rejections)
    : participant_(participant),
      robot_(robot),
      claims_(claims),
      lock_(lock),
      now_ns_(now_ns),
      report_(report),
      events_(events),
      rejections_(rejections),
      granted_(report.counter("claims_granted")),
      refused_(report.counter("claims_refused")),
      owners_(participant, dds::topics::joint_owners(robot), dds::qos::kLatched) {
  publish_owners();  // generation 0: every joint free
  server_ = std::make_unique<dds::Server<wbi::msg::JointClaimRequest, wbi::msg::JointClaimReply>>(
      participant, dds::topics::claim_service(robot),
      [this](const wbi::msg::JointClaimRequest& request, wbi::msg::JointClaimReply& reply) {
        answer(request, reply);
      });
}

ClaimDesk::~ClaimDesk() { server_.reset(); }

std::string ClaimDesk::resolve(const wbi::msg::JointClaimRequest& request,
                               std::vector<int>& joints) const {
  for (const auto& name : request.joints()) {
    const int joint = claims_.find(std::string_view(name.c_str(), name.size()));
    if (joint < 0) {
      return "robot '" + robot_ + "' has no joint '" +
             RejectionLog::without_control_characters(name.c_str()) + "'";
    }
    if (std::find(joints.begin(), joints.end(), joint) != joints.end()) {
      return "joint '" + claims_.joint_name(joint) + "' appears twice";
    }
    joints.push_back(joint);
  }
  return {};
}

std::string ClaimDesk::describe(const Claimant& claimant) const {
  std::string who = participant_.describe_writer(participant_guid(claimant));
  const auto writer = who.rfind(" (writer ");  // a participant has no writer of its own to name
  if (writer != std::string::npos) {
    who.erase(writer);
  }
  std::string text = "'";
  text.append(RejectionLog::printable(claimant.name())).append("' (").append(who).append(")");
  return text;
}

void ClaimDesk::answer(const wbi::msg::JointClaimRequest& request,
                       wbi::msg::JointClaimReply& reply) {
  reply.error() = "";
  reply.contested().clear();
  reply.owners().clear();
  if (request.robot() != robot_) {
    reply.error() = "claim for robot '" + RejectionLog::printable(request.robot().c_str()) +
                    "' sent to robot '" + robot_ + "'";
    return;
  }
  dds::detail::Guid client{};
  if (!dds::detail::parse_guid_hex(request.client_id().c_str(), client)) {
    reply.error() = "client_id '" + RejectionLog::printable(request.client_id().c_str()) +
                    "' is not a GUID (32 hex digits): the claimant cannot be told apart";
    return;
  }
  const std::string_view name(request.controller().c_str(), request.controller().size());
  if (name.empty()) {
    reply.error() = "a claim names its controller (the name its commands carry)";
    return;
  }
  const Claimant who = Claimant::of(client.data(), name);
  std::vector<int> joints;
  if (auto error = resolve(request, joints); !error.empty()) {
    reply.error() = error;
    return;
  }

  if (request.action() == wbi::msg::ClaimAction::RELEASE) {
    std::vector<int> released;
    {
      std::lock_guard lock(lock_);
      released = claims_.release(who, joints);
    }
    if (!released.empty()) {
      const std::string text =
          describe(who) + " released " + std::to_string(released.size()) + " joint(s)";
      runtime::print_line(stderr, "claims: " + text);
      events_.emit(EventSeverity::info, EventKind::claim_changed, text,
                   joint_subject(claims_, released));
      publish_owners();
    }
    return;
  }

  if (joints.empty()) {
    reply.error() = "a claim names at least one joint";
    return;
  }
  JointClaims::Outcome outcome;
  {
    std::lock_guard lock(lock_);
    outcome =
        claims_.claim(who, joints, request.force(), now_ns_.load(), [this](const Claimant& owner) {
          return participant_.participant_gone(participant_guid(owner));
        });
  }
  if (!outcome.granted) {
    std::string held;
    for (const auto& contest : outcome.contested) {
      const std::string owner = RejectionLog::printable(contest.owner.name());
      reply.contested().push_back(claims_.joint_name(contest.joint));
      reply.owners().push_back(owner);
      if (!held.empty()) {
        held += ", ";
      }
      held.append(claims_.joint_name(contest.joint))
          .append(" (held by '")
          .append(owner)
          .append("')");
    }
    const std::string error = "claim of '" + RejectionLog::printable(name) + "' refused: " + held +
                              "; claim with force to take them";
    reply.error() = error;  // the reply's bound (512) may cut a long list; contested has all
    refused_.add();
    report_.set_error(error);
    rejections_.reject("claim", name, error);
    return;
  }
  granted_.add();
  say_granted(who, joints, outcome, request.force());
  publish_owners();
}

void ClaimDesk::say_granted(const Claimant& who, const std::vector<int>& joints,
                            const JointClaims::Outcome& outcome, bool force) {
  const std::string holder = describe(who);
  runtime::print_line(stderr, "claims: " + holder + " holds " + joint_list(claims_, joints));
  std::vector<int> taken_joints;
  std::string taken_from;
  for (const auto& taken : outcome.taken) {
    const std::string owner = describe(taken.owner);
    runtime::print_line(stderr, "claims: joint " + claims_.joint_name(taken.joint) +
                                    " taken from " + owner +
                                    (force ? " by force" : ": its claim had ended"));
    taken_joints.push_back(taken.joint);
    if (taken_from.find(owner) == std::string::npos) {
      taken_from.append(taken_from.empty() ? "" : ", ").append(owner);
    }
  }
  if (force && !taken_joints.empty()) {
    events_.emit(
        EventSeverity::warning, EventKind::claim_forced,
        holder + " took " + joint_list(claims_, taken_joints) + " from " + taken_from + " by force",
        joint_subject(claims_, taken_joints));
  }
  events_.emit(
      EventSeverity::info, EventKind::claim_changed,
      holder + " holds " + joint_list(claims_, joints) +
          (!force && !taken_joints.empty() ? " (taken from " + taken_from + ": its claim had ended)"
                                           : ""),
      joint_subject(claims_, joints));
}

void ClaimDesk::publish_owners() {
  std::lock_guard publishing(publish_mutex_);
  wbi::msg::JointOwners message;
  {
    std::lock_guard lock(lock_);
    message.header().robot(robot_);
    message.header().stamp_ns(now_ns_.load());
    message.header().seq(claims_.generation());
    message.generation(claims_.generation());
    for (int joint = 0; joint < claims_.joint_count(); ++joint) {
      const bool held = claims_.held(joint);
      message.controllers().push_back(held ? std::string(claims_.owner(joint).name()) : "");
      message.participants().push_back(held ? claims_.owner(joint).participant_hex() : "");
    }
  }
  owners_.publish(message);
}

}  // namespace wbi::robot
