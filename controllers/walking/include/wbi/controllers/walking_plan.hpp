// Walking references for a humanoid on flat ground: footsteps from a walking
// command, the divergent component of motion (DCM) of the linear inverted
// pendulum through them, the CoM it implies, swing-foot trajectories and
// per-foot contact weights. Pure geometry and time: no robot, no DDS.
//
// The LIPM at constant CoM height z_c, ω = √(g / z_c):
//   ξ = x + ẋ/ω,   ξ̇ = ω (ξ − r),   ẋ = ω (ξ − x)
// with r the virtual repellent point (VRP; here the ZMP lifted by z_c). The
// VRP stands still on the stance foot's centre during each single support;
// the DCM through the steps follows from the last step backwards
// (Englsberger et al., "Three-dimensional bipedal walking control based on
// divergent component of motion", IEEE T-RO 2015), and each double support
// is a cubic in time joining the DCM and its velocity at its two ends, so
// that ξ and ξ̇ are continuous everywhere, the first double support starting
// from the DCM at the command (standing: the CoM, at rest).
//
// A walk: double support, then per footstep one single support (the other
// foot swings from its pose to the footstep) and one double support. The
// first and the last double support last final_double_support_s (the first
// moves the DCM from between the feet onto the first stance foot: at
// double_support_s that shift would be abrupt); the last ends with the DCM at
// rest between the feet. The VRP of the LIPM switches from one stance foot to
// the next in the middle of each double support (the recursion's virtual
// switch); the CoM follows ẋ = ω (ξ − x) in closed form, phase by phase.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace wbi::controllers::walking {

enum class Foot { left = 0, right = 1 };

// A sole on flat ground: position of the sole frame, yaw about z.
struct FootPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double yaw = 0.0;

  // Of a sole frame's pose in the world (4×4): its origin, the heading of its x axis.
  static FootPose of(const Eigen::Matrix4d& world_H_sole) {
    return {world_H_sole.topRightCorner<3, 1>(),
            std::atan2(world_H_sole(1, 0), world_H_sole(0, 0))};
  }
};

struct Footstep {
  Foot foot = Foot::left;  // the foot that moves there
  FootPose pose;
};

struct WalkingParameters {
  double single_support_s = 0.6;
  double double_support_s = 0.2;
  double final_double_support_s = 0.6;  // the first and the last: to start, to stand still
  double step_height = 0.04;            // swing foot apex above the ground [m]
  double com_height = 0.5;              // z_c of the LIPM [m] (its CoM's height)
  double gravity = 9.81;                // [m/s²]
  double step_width = 0.15;             // lateral distance between the soles [m]
  // Limits of one step, in the frame of the stance foot it starts from (the
  // other foot); a command needing more is cut into more steps, a footstep
  // beyond them is refused.
  double max_step_forward = 0.12;  // [m]
  double max_step_backward = 0.05;
  double max_step_lateral = 0.05;  // beyond step_width, either way [m]
  double max_step_turn = 0.3;      // [rad]
  double min_step_width = 0.1;     // soles' lateral distance never below [m]
  // The VRP's offset from each sole's origin, in the sole frame (the middle
  // of the support rectangle) [m].
  Eigen::Vector3d vrp_offset = Eigen::Vector3d::Zero();
};

// What the walking controller reads at one time: its reference input `walk`,
// kWalkReferenceSize values (position, velocity, acceleration each):
//   0–2   DCM ξ              (velocity ξ̇; acceleration ξ̈)
//   3–5   CoM x              (ẋ, ẍ)
//   6–9   left sole  x, y, z, yaw  (and their derivatives)
//   10–13 right sole x, y, z, yaw
//   14,15 contact weight of the left, right foot: 1 in contact, 0 swinging,
//         ramping in between over a double support (the share of the normal
//         force the foot may carry); derivatives 0
inline constexpr int kWalkReferenceSize = 16;

struct WalkingReference {
  Eigen::Matrix<double, kWalkReferenceSize, 1> position, velocity, acceleration;
};

class WalkingPlan {
 public:
  // Throws wbi::Error naming a parameter out of its range (non-positive
  // durations, heights or limits).
  explicit WalkingPlan(WalkingParameters parameters);

  const WalkingParameters& parameters() const { return p_; }
  double omega() const;

  // Standing at time t on these feet, the CoM at com, at rest. Forgets any walk.
  void stand(double t, const FootPose& left, const FootPose& right, const Eigen::Vector3d& com);

  // Walk by (dx, dy, dyaw) relative to the middle of the feet and their mean
  // heading at time t: straight to (dx, dy) in steps within the limits, then
  // turning in place to dyaw, then the feet side by side at step_width. The
  // first step is by the foot that the direction of travel favours. Returns
  // "" when planned, else one line saying why not (a NaN or infinite value,
  // the robot is walking already (walking(t)), a goal farther than 100 m or
  // turned more than 4π, a footstep it would need out of the limits), and the
  // plan is unchanged. A goal where the robot stands already plans nothing.
  // Allocates nothing (buffers reserved at construction for the longest goal;
  // a copied plan's are not).
  std::string walk_to(double t, double dx, double dy, double dyaw);

  // Walk the given footsteps (world frame) from time t, the feet alternating.
  // Returns "" or one line naming the first footstep out of the limits
  // relative to the stance foot it starts from (the other foot, where it
  // stands then), or that the robot is walking already; unchanged then.
  std::string walk(double t, const std::vector<Footstep>& footsteps);

  bool walking(double t) const;  // a walk is planned and not over at t
  double end_time() const;       // when the last walk ends (standing: its stand time)
  const std::vector<Footstep>& footsteps() const { return steps_; }

  // The references at time t (before the walk: standing; after: standing at
  // its end). No allocation.
  void sample(double t, WalkingReference& out) const;

 private:
  enum class PhaseKind { double_support, single_support, rest };
  // One piece of the plan, from `begin` for `duration` (rest: for ever).
  struct Phase {
    PhaseKind kind = PhaseKind::rest;
    double begin = 0.0, duration = 0.0;
    // DCM: double support, ξ(τ) = Σ dcm[k] τ^k (a cubic); single support,
    // ξ(τ) = dcm[0] + e^{ωτ} dcm[1] (VRP, offset from it); rest, ξ = dcm[0].
    std::array<Eigen::Vector3d, 4> dcm{};
    Eigen::Vector3d com_begin = Eigen::Vector3d::Zero();
    std::array<FootPose, 2> feet_begin{};  // left, right when the phase begins
    int step = -1;                         // single support: the footstep swung to
    std::array<double, 2> weight_begin{1.0, 1.0}, weight_end{1.0, 1.0};
  };

  std::string check_parameters() const;
  std::string check_and_unwrap(std::array<FootPose, 2> feet);  // scratch_steps_ from these feet
  std::string plan(double t);                                  // scratch_steps_ from time t
  void fill_timing(double t, const std::array<FootPose, 2>& feet);
  void fill_dcm(const Eigen::Vector3d& dcm_now);
  void fill_com(const Eigen::Vector3d& com_now);
  const Phase& phase_at(double t) const;
  void dcm_at(const Phase& phase, double tau, Eigen::Vector3d& x, Eigen::Vector3d& v,
              Eigen::Vector3d& a) const;
  void com_at(const Phase& phase, double tau, Eigen::Vector3d& x, Eigen::Vector3d& v,
              Eigen::Vector3d& a) const;
  Eigen::Vector3d vrp(const FootPose& sole) const;

  WalkingParameters p_;
  std::vector<Footstep> steps_;
  std::vector<Phase> phases_;  // in time order; the last is the rest after the walk
  // walk_to builds here, then swaps: reserved at construction for the
  // longest walk_to, so that planning one allocates nothing.
  std::vector<Footstep> scratch_steps_;
  std::vector<Phase> scratch_phases_;
};

}  // namespace wbi::controllers::walking
