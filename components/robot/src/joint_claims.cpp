#include "joint_claims.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace wbi::robot {

Claimant Claimant::of(const std::uint8_t* guid, std::string_view controller) {
  Claimant claimant;
  std::copy_n(guid, claimant.participant.size(), claimant.participant.begin());
  const std::size_t length = std::min(controller.size(), kMaxName);
  std::memcpy(claimant.controller.data(), controller.data(), length);
  claimant.controller[length] = '\0';
  return claimant;
}

std::string Claimant::participant_hex() const {
  std::string text(participant.size() * 2, '0');
  for (std::size_t i = 0; i < participant.size(); ++i) {
    std::snprintf(&text[2 * i], 3, "%02x", participant[i]);
  }
  return text;
}

JointClaims::JointClaims(std::vector<std::string> joint_names, std::int64_t lapse_ns,
                         bool require_claims)
    : joint_names_(std::move(joint_names)),
      owners_(joint_names_.size()),
      lapse_ns_(lapse_ns),
      require_claims_(require_claims) {}

int JointClaims::find(std::string_view joint) const {
  const auto found = std::find(joint_names_.begin(), joint_names_.end(), joint);
  return found == joint_names_.end() ? -1 : static_cast<int>(found - joint_names_.begin());
}

JointClaims::Outcome JointClaims::claim(const Claimant& who, std::span<const int> joints,
                                        bool force, std::int64_t now_ns,
                                        const std::function<bool(const Claimant&)>& gone) {
  Outcome outcome;
  for (const int joint : joints) {
    const Owner& owner = owners_[joint];
    if (!owner.held || owner.by == who) {
      continue;
    }
    const bool silent = lapse_ns_ > 0 && now_ns - owner.last_command_ns > lapse_ns_;
    const bool ended = silent || gone(owner.by);
    (force || ended ? outcome.taken : outcome.contested).push_back({joint, owner.by});
  }
  if (!outcome.contested.empty()) {
    outcome.taken.clear();
    return outcome;
  }
  bool changed = false;
  for (const int joint : joints) {
    Owner& owner = owners_[joint];
    changed = changed || !owner.held || !(owner.by == who);
    owner = {true, who, now_ns};
  }
  if (changed) {
    ++generation_;
  }
  outcome.granted = true;
  return outcome;
}

std::vector<int> JointClaims::release(const Claimant& who, std::span<const int> joints) {
  std::vector<int> released;
  for (int joint = 0; joint < joint_count(); ++joint) {
    const bool listed =
        joints.empty() || std::find(joints.begin(), joints.end(), joint) != joints.end();
    if (listed && owners_[joint].held && owners_[joint].by == who) {
      owners_[joint] = {};
      released.push_back(joint);
    }
  }
  if (!released.empty()) {
    ++generation_;
  }
  return released;
}

std::string JointClaims::refusal(const Claimant& who, int joint) const {
  const Owner& owner = owners_[joint];
  const std::string name = "joint '" + joint_names_[joint] + "'";
  if (!owner.held) {
    return name + " is not claimed by '" + std::string(who.name()) +
           "': this robot requires a claim before commands (require_claims)";
  }
  if (owner.by.name() == who.name()) {
    return name + " is held by '" + std::string(owner.by.name()) + "' of participant " +
           owner.by.participant_hex() + ", not by this sender's participant " +
           who.participant_hex();
  }
  return name + " is held by '" + std::string(owner.by.name()) + "'";
}

}  // namespace wbi::robot
