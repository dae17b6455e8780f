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
// foot swings from its pose to the footstep) and one double support, the
// last one longer (final_double_support_s) ending with the DCM at rest
// between the feet.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace wbi::controllers::walking {

enum class Foot { left = 0, right = 1 };

// A sole on flat ground: position of the sole frame, yaw about z.
struct FootPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double yaw = 0.0;
};

struct Footstep {
  Foot foot = Foot::left;  // the foot that moves there
  FootPose pose;
};

struct WalkingParameters {
  double single_support_s = 0.6;
  double double_support_s = 0.2;
  double final_double_support_s = 0.6;  // the last, to stand still
  double step_height = 0.04;             // swing foot apex above the ground [m]
  double com_height = 0.5;               // z_c of the LIPM [m] (its CoM's height)
  double gravity = 9.81;                 // [m/s²]
  double step_width = 0.15;              // lateral distance between the soles [m]
  // Limits of one step, in the frame of the foot it starts from; a command
  // needing more is cut into more steps, a footstep beyond them is refused.
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
  // turned more than 4π), and the plan is unchanged.
  std::string walk_to(double t, double dx, double dy, double dyaw);

  // Walk the given footsteps (world frame) from time t. Returns "" or one line
  // naming the first footstep out of the limits relative to the foot it
  // starts from, or that the robot is walking already; unchanged then.
  std::string walk(double t, const std::vector<Footstep>& footsteps);

  bool walking(double t) const;  // a walk is planned and not over at t
  double end_time() const;       // when the last walk ends (standing: its stand time)
  const std::vector<Footstep>& footsteps() const { return steps_; }

  // The references at time t (before the walk: standing; after: standing at
  // its end). No allocation.
  void sample(double t, WalkingReference& out) const;

 private:
  WalkingParameters p_;
  std::vector<Footstep> steps_;
  // The implementation's own members follow (phases, DCM boundary values,
  // swing polynomials), sized when a walk is planned.
};

}  // namespace wbi::controllers::walking
