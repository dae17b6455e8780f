#include "simulated_motion.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "wbi/model/crba.hpp"
#include "wbi/model/data.hpp"
#include "wbi/model/rnea.hpp"
#include "wbi/sim/sim_backend.hpp"

namespace wbi::bench {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSimStepS = 1e-4;    // truth grid: 10 plant steps per control tick
constexpr int kStepsPerTick = 10;     // control at 1 kHz
constexpr double kBandwidthHz = 8.0;  // PD: critically damped, per joint inertia

// The reference each joint tracks: a 0.5 Hz squat (hip, knee, ankle pitch
// coordinated, torso leaning), 1 Hz arm swings, a 2 Hz wrist wave, slow head
// and torso turns, and two quick minimum-jerk reaches of each arm.
std::map<std::string, JointMotion> references() {
  const auto squat = [](double depth, double sign) {
    // sign · depth · (1 − cos ωt) / 2: from 0 down to sign·depth and back.
    return JointMotion{sign * 0.5 * depth, {{0.5 * depth, 0.5, -sign * 0.5 * kPi}}, {}};
  };
  const auto wave = [](double offset, double amplitude, double hz, double phase) {
    return JointMotion{offset, {{amplitude, hz, phase}}, {}};
  };
  std::map<std::string, JointMotion> r;
  for (const std::string side : {"l_", "r_"}) {
    const double mirror = side == "l_" ? 0.0 : kPi;
    r[side + "hip_pitch"] = squat(0.6, -1.0);
    r[side + "knee"] = squat(1.2, 1.0);
    r[side + "ankle_pitch"] = squat(0.6, -1.0);
    r[side + "hip_roll"] = wave(0.05, 0.05, 0.5, 0.0);
    r[side + "ankle_roll"] = wave(0.0, 0.05, 0.5, kPi);
    r[side + "hip_yaw"] = wave(0.0, 0.1, 0.25, mirror);
    r[side + "shoulder_pitch"] = wave(-0.4, 0.6, 1.0, mirror);
    r[side + "shoulder_roll"] = wave(0.35, 0.15, 0.5, 0.0);
    r[side + "shoulder_yaw"] = wave(0.0, 0.2, 0.7, mirror);
    r[side + "elbow"] = JointMotion{0.8, {{0.4, 1.0, 0.5 * kPi + mirror}, {0.1, 2.0, 0.0}}, {}};
    r[side + "wrist_yaw"] = wave(0.0, 0.4, 2.0, mirror);
    r[side + "wrist_pitch"] = wave(0.0, 0.3, 1.5, 0.0);
  }
  r["r_shoulder_pitch"].steps = {{2.0, 0.35, -0.8}, {3.5, 0.35, 0.8}};
  r["l_elbow"].steps = {{4.2, 0.3, 0.6}, {5.0, 0.3, -0.6}};
  r["torso_pitch"] = squat(0.2, 1.0);
  r["torso_roll"] = wave(0.0, 0.05, 0.5, 0.0);
  r["torso_yaw"] = wave(0.0, 0.25, 0.5, 0.0);
  r["neck_pitch"] = wave(0.0, 0.2, 0.4, 0.0);
  r["neck_roll"] = wave(0.0, 0.1, 0.6, 0.0);
  r["neck_yaw"] = wave(0.0, 0.5, 0.3, 0.0);
  return r;
}

}  // namespace

SampledMotion::SampledMotion(double dt_s, Eigen::MatrixXd q, Eigen::MatrixXd dq,
                             Eigen::MatrixXd ddq)
    : dt_s_(dt_s), q_(std::move(q)), dq_(std::move(dq)), ddq_(std::move(ddq)) {}

double SampledMotion::interpolate(const Eigen::MatrixXd& m, int j, double t) const {
  const double x = std::clamp(t / dt_s_, 0.0, static_cast<double>(m.cols() - 1));
  const auto i = std::min(static_cast<Eigen::Index>(x), m.cols() - 2);
  const double u = x - static_cast<double>(i);
  return (1.0 - u) * m(j, i) + u * m(j, i + 1);
}

void SampledMotion::evaluate(int j, double t, double& q, double& dq, double& ddq) const {
  q = interpolate(q_, j, t);
  dq = interpolate(dq_, j, t);
  ddq = interpolate(ddq_, j, t + 0.5 * dt_s_);
}

SampledMotion simulate_humanoid_motion(const std::string& urdf, double duration_s,
                                       bool joint_friction) {
  robot_config::RobotConfig config;
  config.urdf = urdf;
  config.fixed_base = true;
  config.wbi.step = kSimStepS;
  config.wbi.substeps = 1;
  robot_config::complete_from_urdf(config);  // every joint's URDF <dynamics>
  if (!joint_friction) {
    for (auto& [name, joint] : config.joints) {
      joint.friction = 0.0;
    }
  }
  sim::SimBackend sim(config);
  sim.configure();
  const auto& description = sim.description();
  const int n = description.n_joints();
  std::vector<JointMotion> reference(static_cast<std::size_t>(n));
  for (const auto& [name, motion] : references()) {
    reference[static_cast<std::size_t>(description.joint_index(name))] = motion;
  }
  // Start on the reference, at its velocity.
  Eigen::VectorXd q_r(n);
  Eigen::VectorXd dq_r(n);
  Eigen::VectorXd ddq_r(n);
  const auto reference_at = [&](double t) {
    for (int j = 0; j < n; ++j) {
      reference[static_cast<std::size_t>(j)].evaluate(t, q_r(j), dq_r(j), ddq_r(j));
    }
  };
  reference_at(0.0);
  sim.set_state(q_r, dq_r);
  sim.activate();

  // PD + gravity with inertia-scaled gains (mass-matrix diagonal at the start)
  // and the reference acceleration as feed-forward, on the true state.
  const model::Model& model = sim.model();
  model::Data data(model);
  const Eigen::VectorXd inertia = model::mass_matrix(model, data, q_r).diagonal();
  const double omega = 2.0 * kPi * kBandwidthHz;

  const auto ticks = static_cast<Eigen::Index>(std::llround(duration_s * 1e3));
  const Eigen::Index samples = ticks * kStepsPerTick + 1;
  Eigen::MatrixXd q(n, samples);
  Eigen::MatrixXd dq(n, samples);
  Eigen::MatrixXd ddq(n, samples);
  const sim::GroundTruth& truth = sim.ground_truth();
  q.col(0) = truth.q;
  dq.col(0) = truth.nu;
  ddq.col(0) = ddq_r;
  auto& commands = sim.commands();
  for (Eigen::Index tick = 0; tick < ticks; ++tick) {
    const double t = static_cast<double>(tick) * 1e-3;
    reference_at(t);
    const Eigen::VectorXd& gravity = model::gravity_forces(model, data, truth.q, config.gravity);
    for (int j = 0; j < n; ++j) {
      const double feedback =
          omega * omega * (q_r(j) - truth.q(j)) + 2.0 * omega * (dq_r(j) - truth.nu(j)) + ddq_r(j);
      commands.mode[static_cast<std::size_t>(j)] = actuation::OutputMode::kTorque;
      commands.value(j) = gravity(j) + inertia(j) * feedback;
    }
    sim.write(sim.stamp(), std::chrono::milliseconds(1));
    for (int s = 1; s <= kStepsPerTick; ++s) {
      sim.step();
      const Eigen::Index i = tick * kStepsPerTick + s;
      q.col(i) = truth.q;
      dq.col(i) = truth.nu;
      ddq.col(i) = truth.dnu;
    }
  }
  return SampledMotion(kSimStepS, std::move(q), std::move(dq), std::move(ddq));
}

}  // namespace wbi::bench
