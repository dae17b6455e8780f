// The humanoid motion of the estimator benchmark, from the simulator: the
// project's 30-joint humanoid (models/humanoid.urdf, pelvis fixed so that the
// motion does not depend on balance) tracks a squat with arm swings, a wave
// and two quick reaches under joint-space PD + gravity at 1 kHz. The truth
// (q, dq, ddq of every joint) is the simulator's ground truth on a 0.1 ms grid,
// deterministic, generated at start-up.
#pragma once

#include <Eigen/Core>
#include <string>

#include "motion.hpp"

namespace wbi::bench {

// A motion known on a uniform grid, linearly interpolated in between.
class SampledMotion final : public Motion {
 public:
  // q, dq: (joints × samples) at t_i = i·dt_s. ddq(·, i): the acceleration
  // over (t_(i-1), t_i] (semi-implicit Euler), i.e. at t_i − dt_s/2.
  SampledMotion(double dt_s, Eigen::MatrixXd q, Eigen::MatrixXd dq, Eigen::MatrixXd ddq);
  int joints() const override { return static_cast<int>(q_.rows()); }
  double duration_s() const { return dt_s_ * static_cast<double>(q_.cols() - 1); }
  void evaluate(int j, double t, double& q, double& dq, double& ddq) const override;

 private:
  double interpolate(const Eigen::MatrixXd& m, int j, double t) const;

  double dt_s_;
  Eigen::MatrixXd q_;
  Eigen::MatrixXd dq_;
  Eigen::MatrixXd ddq_;
};

// Simulates the humanoid (urdf: models/humanoid.urdf) for duration_s.
// joint_friction: the URDF's Coulomb friction (stick-slip notches in ddq at
// every velocity reversal, deep on the light wrists). Throws when the URDF
// cannot be loaded.
SampledMotion simulate_humanoid_motion(const std::string& urdf, double duration_s,
                                       bool joint_friction = true);

}  // namespace wbi::bench
