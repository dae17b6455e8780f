// Ground-truth joint motions for the estimator benchmark and how an encoder
// samples them. A Motion gives exact q, dq, ddq of every joint at any time:
// analytic ones (sums of sinusoids and minimum-jerk steps, this file) and the
// humanoid motion recorded from the simulator (simulated_motion.hpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace wbi::bench {

// The benchmark's encoders: 1 kHz, 14 bits; the humanoid motion's length.
constexpr double kRateHz = 1000.0;
constexpr double kCounts = 16384.0;
constexpr double kHumanoidDurationS = 6.0;

class Motion {
 public:
  virtual ~Motion() = default;
  virtual int joints() const = 0;
  // Ground truth of joint j at time t (s).
  virtual void evaluate(int j, double t, double& q, double& dq, double& ddq) const = 0;
};

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

class AnalyticMotion final : public Motion {
 public:
  explicit AnalyticMotion(std::vector<JointMotion> joints) : joints_(std::move(joints)) {}
  int joints() const override { return static_cast<int>(joints_.size()); }
  void evaluate(int j, double t, double& q, double& dq, double& ddq) const override {
    joints_[static_cast<std::size_t>(j)].evaluate(t, q, dq, ddq);
  }

 private:
  std::vector<JointMotion> joints_;
};

// `joints` joints moving as one sinusoid of the given frequency and amplitude,
// with phases spread over the joints.
AnalyticMotion sinusoid_motion(double frequency_hz, double amplitude_rad, int joints);

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
