// Who owns which joint of a robot: one owner per joint, enforced on every
// command (idl/claims.idl). The rules, in one place:
//   claim     granted as a whole when every joint is free, already the
//             claimant's, or its claim has ended; else refused as a whole,
//             naming each contested joint and its owner. `force` takes joints
//             from a live owner (a supervisor, an e-stop tool).
//   ended     an owner's claim ends when its participant is gone (left
//             discovery, or its process on this host ended) or when it sent
//             no command for `lapse` (the watchdog time: its streaming joints
//             are then in the watchdog's hold). A silent owner that nobody
//             replaced keeps its joints: its next command renews the claim.
//   release   the claimant's joints become free.
//   command   applied only when each of its joints is free or the sender's
//             own; a free joint takes any sender unless claims are required.
// No DDS here: the caller says who the claimant is and whether a participant
// is gone, so the rules are tested on given inputs (test_joint_claims).
// Not thread-safe: the actuator side calls it under its lock. The command
// path (first_refused, commanded) never allocates.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace wbi::robot {

// A controller as the robot knows it: the participant it speaks from and the
// name its commands carry. Two controllers in one process differ by name.
struct Claimant {
  static constexpr std::size_t kMaxName = 64;   // idl BoundedName
  std::array<std::uint8_t, 12> participant{};   // RTPS GUID prefix
  std::array<char, kMaxName + 1> controller{};  // null-terminated

  // From any GUID of the participant (its first 12 bytes) and a name. Never allocates.
  static Claimant of(const std::uint8_t* guid, std::string_view controller);
  std::string_view name() const { return controller.data(); }
  std::string participant_hex() const;  // 24 lower-case hex digits
  bool operator==(const Claimant& other) const = default;
};

class JointClaims {
 public:
  // lapse_ns ≤ 0: a silent owner keeps its claim (the watchdog is off).
  JointClaims(std::vector<std::string> joint_names, std::int64_t lapse_ns, bool require_claims);

  struct Contest {
    int joint;
    Claimant owner;
  };
  struct Outcome {
    bool granted = false;
    std::vector<Contest> contested;  // refused: the joints others hold
    std::vector<Contest> taken;      // granted: joints taken from another owner (forced or ended)
  };
  // `gone(owner)`: whether the owner's participant has left (a DDS question).
  Outcome claim(const Claimant& who, std::span<const int> joints, bool force, std::int64_t now_ns,
                const std::function<bool(const Claimant&)>& gone);
  // Frees the claimant's joints among `joints` (all of its joints when empty);
  // returns those it held (their indices).
  std::vector<int> release(const Claimant& who, std::span<const int> joints);

  // The position in `joints` of the first joint `who` may not command, or -1.
  // Indices out of range are not this check's to refuse (the joint controller
  // names them): they are skipped.
  template <class Index>
  int first_refused(const Claimant& who, std::span<const Index> joints) const {
    for (std::size_t k = 0; k < joints.size(); ++k) {
      const auto joint = static_cast<std::size_t>(joints[k]);
      if (joint < owners_.size() && !may_command(who, static_cast<int>(joint))) {
        return static_cast<int>(k);
      }
    }
    return -1;
  }
  // An applied command: renews its sender's claims on these joints.
  template <class Index>
  void commanded(const Claimant& who, std::span<const Index> joints, std::int64_t now_ns) {
    for (const auto joint : joints) {
      if (static_cast<std::size_t>(joint) < owners_.size() && owners_[joint].held &&
          owners_[joint].by == who) {
        owners_[joint].last_command_ns = now_ns;
      }
    }
  }

  bool held(int joint) const { return owners_[joint].held; }
  const Claimant& owner(int joint) const { return owners_[joint].by; }
  const std::string& joint_name(int joint) const { return joint_names_[joint]; }
  int joint_count() const { return static_cast<int>(joint_names_.size()); }
  // The joint's index, -1 when the robot has none of that name.
  int find(std::string_view joint) const;
  // +1 at every change of owner (what wbi/<robot>/claims/owners carries).
  std::uint64_t generation() const { return generation_; }
  bool require_claims() const { return require_claims_; }

  // "joint 'a' is held by 'pd'": why `who` may not command `joint`.
  std::string refusal(const Claimant& who, int joint) const;

 private:
  struct Owner {
    bool held = false;
    Claimant by;
    std::int64_t last_command_ns = 0;  // claim time, then its last applied command
  };
  bool may_command(const Claimant& who, int joint) const {
    const Owner& owner = owners_[joint];
    return owner.held ? owner.by == who : !require_claims_;
  }

  std::vector<std::string> joint_names_;
  std::vector<Owner> owners_;
  std::int64_t lapse_ns_;
  bool require_claims_;
  std::uint64_t generation_ = 0;
};

}  // namespace wbi::robot
