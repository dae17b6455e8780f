// The planner's posture in time (no DDS, no robot): where the arm should be
// at t seconds of robot time, with the velocity and acceleration there, so
// that the controller's reference input carries a point smoothly to the
// next.
//
//   t < start_s                 from                                  (at rest)
//   start_s ≤ t < t_move        from + s(τ) (target − from), minimum jerk,
//                               s(τ) = 10τ³ − 15τ⁴ + 6τ⁵, τ = (t − start_s) / move_s
//   t_move ≤ t < t_sway         target + sway (1 − cos ω(t − t_move)) / 2, ω = 2π sway_hz:
//                               sway_periods periods out and back, from rest to rest
//   after                       target                                (at rest)
//
// with t_move = start_s + move_s and t_sway = t_move + sway_periods / sway_hz.
// Position and velocity are continuous everywhere; the acceleration jumps
// where the sway begins and ends (by sway ω²/2).
#pragma once

#include <Eigen/Core>

namespace lab {

struct PostureTrajectory {
  Eigen::VectorXd from;    // [n] rad: the posture it starts from
  Eigen::VectorXd target;  // [n] rad
  Eigen::VectorXd sway;    // [n] rad: each joint's sway about the target (0: none)
  double start_s = 1.5;    // the move begins
  double move_s = 2.0;     // its duration (> 0)
  double sway_hz = 0.5;    // > 0
  int sway_periods = 1;    // ≥ 0

  // x, v, a at t: sized n by the caller; no allocation.
  void at(double t, Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& a) const;
  // When the posture is the target for good.
  double end_s() const;
};

}  // namespace lab
