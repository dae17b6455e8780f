#include "motion.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace wbi::bench {

void JointMotion::evaluate(double t, double& q, double& dq, double& ddq) const {
  q = offset_rad;
  dq = 0.0;
  ddq = 0.0;
  for (const auto& wave : waves) {
    const double w = 2.0 * std::numbers::pi * wave.frequency_hz;
    const double s = std::sin(w * t + wave.phase_rad);
    const double c = std::cos(w * t + wave.phase_rad);
    q += wave.amplitude_rad * s;
    dq += wave.amplitude_rad * w * c;
    ddq -= wave.amplitude_rad * w * w * s;
  }
  for (const auto& step : steps) {
    const double u = (t - step.start_s) / step.duration_s;
    if (u <= 0.0) {
      continue;
    }
    if (u >= 1.0) {
      q += step.height_rad;
      continue;
    }
    const double u2 = u * u;
    const double u3 = u2 * u;
    q += step.height_rad * (10.0 * u3 - 15.0 * u3 * u + 6.0 * u3 * u2);
    dq += step.height_rad / step.duration_s * (30.0 * u2 - 60.0 * u3 + 30.0 * u2 * u2);
    ddq += step.height_rad / (step.duration_s * step.duration_s) *
           (60.0 * u - 180.0 * u2 + 120.0 * u3);
  }
}

AnalyticMotion sinusoid_motion(double frequency_hz, double amplitude_rad, int joints) {
  std::vector<JointMotion> motion;
  for (int j = 0; j < joints; ++j) {
    JointMotion joint;
    joint.waves.push_back({amplitude_rad, frequency_hz, 2.0 * std::numbers::pi * j / joints});
    motion.push_back(joint);
  }
  return AnalyticMotion(std::move(motion));
}

EncoderRecording record(const Motion& motion, double rate_hz, double duration_s, double counts,
                        double drop_probability, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto joints = static_cast<Eigen::Index>(motion.joints());
  const double step = 2.0 * std::numbers::pi / counts;
  Eigen::VectorXd zero(joints);
  for (Eigen::Index j = 0; j < joints; ++j) {
    zero(j) = step * uniform(rng);
  }
  std::vector<std::int64_t> stamps;
  const auto total = static_cast<std::int64_t>(duration_s * rate_hz);
  const double period_ns = 1e9 / rate_hz;
  for (std::int64_t k = 0; k < total; ++k) {
    if (k > 0 && uniform(rng) < drop_probability) {
      continue;
    }
    stamps.push_back(std::llround(static_cast<double>(k) * period_ns));
  }
  EncoderRecording out;
  const auto samples = static_cast<Eigen::Index>(stamps.size());
  out.q_measured.resize(joints, samples);
  out.q_true.resize(joints, samples);
  out.dq_true.resize(joints, samples);
  out.ddq_true.resize(joints, samples);
  for (Eigen::Index k = 0; k < samples; ++k) {
    const double t = 1e-9 * static_cast<double>(stamps[static_cast<std::size_t>(k)]);
    for (Eigen::Index j = 0; j < joints; ++j) {
      double q = 0.0;
      double dq = 0.0;
      double ddq = 0.0;
      motion.evaluate(static_cast<int>(j), t, q, dq, ddq);
      out.q_true(j, k) = q;
      out.dq_true(j, k) = dq;
      out.ddq_true(j, k) = ddq;
      // The encoder counts whole steps from its own zero.
      out.q_measured(j, k) = step * std::round((q + zero(j)) / step) - zero(j);
    }
  }
  out.stamp_ns = std::move(stamps);
  return out;
}

}  // namespace wbi::bench
