// Ground-truth joint motions for the estimator benchmark: sums of sinusoids and
// minimum-jerk smooth steps, with exact position, velocity and acceleration.
// The humanoid-like motion is synthetic: the simulator does not exist yet, so
// it imitates a gait (0.9 Hz and two harmonics per joint) with arm/torso
// repositioning (smooth steps) instead of replaying a simulated humanoid.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace wbi::bench {

struct Sinusoid {
  double amplitude_rad;
  double frequency_hz;
  double phase_rad;
};

// Minimum-jerk transition of `height` from start_s to start_s + duration_s:
// h (10u³ - 15u⁴ + 6u⁵), u = (t - start) / duration.
struct SmoothStep {
  double start_s;
  double duration_s;
  double height_rad;
};

struct JointMotion {
  double offset_rad = 0.0;
  std::vector<Sinusoid> waves;
  std::vector<SmoothStep> steps;

  // Exact q, dq, ddq at time t.
  void evaluate(double t, double& q, double& dq, double& ddq) const;
};

struct Motion {
  std::string name;
  std::vector<JointMotion> joints;
};

// `joints` joints moving as one sinusoid of the given frequency and amplitude,
// with phases spread over the joints.
Motion sinusoid_motion(double frequency_hz, double amplitude_rad, int joints);
// 32 joints: gait-like harmonics plus smooth repositioning steps; fixed seed.
Motion humanoid_motion(int joints = 32, std::uint32_t seed = 7);

// Samples of a motion as an encoder sees them.
struct EncoderRecording {
  std::vector<std::int64_t> stamp_ns;  // (samples)
  Eigen::MatrixXd q_measured;          // (joints × samples) quantised positions
  Eigen::MatrixXd q_true;              // (joints × samples)
  Eigen::MatrixXd dq_true;             // (joints × samples)
  Eigen::MatrixXd ddq_true;            // (joints × samples)
};

// Samples `motion` at `rate_hz` for `duration_s`, quantised to `counts` per
// revolution with a random encoder zero per joint. drop_probability > 0
// removes samples at random (the stamps then skip).
EncoderRecording record(const Motion& motion, double rate_hz, double duration_s, double counts,
                        double drop_probability = 0.0, std::uint32_t seed = 11);

}  // namespace wbi::bench
