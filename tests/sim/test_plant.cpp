// Plant-level tests of wbi::sim (no DDS): energy, standing, determinism, sensors, pushes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <map>

#include "sim_test_common.hpp"
#include "wbi/model/com.hpp"
#include "wbi/model/rnea.hpp"

namespace wbi::sim::test {
namespace {

// Pendulum (pendulum.urdf, no <dynamics>: no damping, no friction) released at
// 1 rad with zero torque for 10 s at h = 1 ms, semi-implicit Euler. Symplectic
// Euler conserves a modified energy: the true energy oscillates by O(ω h)
// relative to the swing energy, with no secular drift. With ω = √(m g l/I) ≈ 4.0 rad/s
// and h = 1e-3 that is ≈ 0.4 %; tolerance 1 % of m g l_c (1 − cos 1) ≈ 4.5 J.
TEST(SimPlant, PendulumConservesEnergy) {
  RobotConfig c;
  c.urdf = model_path("pendulum.urdf");
  c.initial_joint_positions["hinge"] = 1.0;
  SimBackend sim(c);
  sim.configure();  // INACTIVE: every joint IDLE (zero torque)
  const double e0 = sim.mechanical_energy();
  const double swing = 2.0 * 9.81 * 0.5 * (1.0 - std::cos(1.0));
  double max_dev = 0.0;
  double e_end = e0;
  for (int k = 0; k < 10000; ++k) {
    sim.write(sim.stamp(), std::chrono::milliseconds(1));
    sim.step();
    if (k % 10 == 0 || k == 9999) {
      e_end = sim.mechanical_energy();
      max_dev = std::max(max_dev, std::abs(e_end - e0));
    }
  }
  std::cout << "[measured] pendulum 10 s: max |E - E0| = " << max_dev << " J ("
            << 100.0 * max_dev / swing << " % of the swing energy), E(10 s) - E0 = " << e_end - e0
            << " J\n";
  EXPECT_LT(max_dev, 0.01 * swing);
  EXPECT_LT(std::abs(e_end - e0), 0.01 * swing);
  // still swinging with the same amplitude (no numerical damping)
  EXPECT_NEAR(sim.ground_truth().time, 10.0, 1e-9);
}

// Double pendulum (no damping, no friction, far from the joint limit) with
// armature, released at (1, −0.5) rad with zero torque for 5 s. The energy the
// plant reports is ½ q̇ᵀ(M + diag(armature))q̇ + V, the one its dynamics conserve
// (the armature is constant, so νᵀ(Ṁ/2 − C)ν = 0 still holds). Semi-implicit
// Euler is first order: the energy error halves with the substep, and stays
// well within 1 % of the swing energy at the default h = 0.5 ms.
struct EnergyRun {
  double max_dev = 0.0;  // max |E − E0| [J]
  double e0 = 0.0;
  double q1_end = 0.0;  // joint1 at the end (does the armature act?)
};

EnergyRun double_pendulum_energy(const std::map<std::string, double>& armature, int substeps) {
  RobotConfig c;
  c.urdf = model_path("double_pendulum.urdf");
  c.initial_joint_positions = {{"joint1", 1.0}, {"joint2", -0.5}};
  for (const char* joint : {"joint1", "joint2"}) {  // no damping, no friction
    c.joints[joint].armature = armature.count(joint) != 0 ? armature.at(joint) : 0.0;
  }
  c.wbi.substeps = substeps;
  SimBackend sim(c);
  sim.configure();  // INACTIVE: every joint IDLE (zero torque)
  EnergyRun r;
  r.e0 = sim.mechanical_energy();
  for (int k = 0; k < 5000; ++k) {
    sim.write(sim.stamp(), std::chrono::milliseconds(1));
    sim.step();
    r.max_dev = std::max(r.max_dev, std::abs(sim.mechanical_energy() - r.e0));
  }
  r.q1_end = sim.ground_truth().q[0];
  return r;
}

TEST(SimPlant, DoublePendulumWithArmatureConservesEnergyToFirstOrder) {
  const std::map<std::string, double> armature{{"joint1", 0.4}, {"joint2", 0.15}};
  const EnergyRun coarse = double_pendulum_energy(armature, 2);  // h = 0.5 ms
  const EnergyRun fine = double_pendulum_energy(armature, 4);    // h = 0.25 ms
  const EnergyRun none = double_pendulum_energy({}, 2);
  // swing energy: E0 minus the energy hanging at rest
  RobotConfig hanging;
  hanging.urdf = model_path("double_pendulum.urdf");
  SimBackend rest(hanging);
  rest.configure();
  const double swing = coarse.e0 - rest.mechanical_energy();
  std::cout << "[measured] double pendulum with armature, 5 s: max |E - E0| = " << coarse.max_dev
            << " J at h = 0.5 ms, " << fine.max_dev << " J at h = 0.25 ms (ratio "
            << coarse.max_dev / fine.max_dev << "); swing energy " << swing << " J\n";
  ASSERT_GT(swing, 1.0);
  EXPECT_LT(coarse.max_dev, 0.01 * swing);
  EXPECT_GT(coarse.max_dev / fine.max_dev, 1.6);  // first order: 2
  EXPECT_LT(coarse.max_dev / fine.max_dev, 2.5);
  EXPECT_EQ(none.e0, coarse.e0);                           // at rest the armature stores no energy
  EXPECT_GT(std::abs(coarse.q1_end - none.q1_end), 1e-2);  // and it does change the motion
}

struct StandResult {
  double settle_height = 0.0;      // base height change from the start to 0.5 s (contact sag)
  double settle_horizontal = 0.0;  // base horizontal offset at 0.5 s (joint PD compliance)
  double drift_height = 0.0;      // |Δz| of the mean base position, [0.5 s, 1.5 s] → last second
  double drift_horizontal = 0.0;  // horizontal distance between the same two means
  double sway_horizontal = 0.0;   // max horizontal distance from the settled position after 0.5 s
  double max_tilt = 0.0;          // max base rotation angle from the start
  double max_joint_dev = 0.0;     // max |q_j − q_j0| over the run
  double min_height = 1e9;
  double fz_total = 0.0;
  double ft_z_sum = 0.0;
  Eigen::Vector3d imu_accel = Eigen::Vector3d::Zero();
  Eigen::VectorXd q_end;
  Eigen::VectorXd position_end;  // encoder readings at the end
};

StandResult stand(RobotConfig c, double seconds) {
  StiffSim held(c);
  SimBackend& sim = held.sim;
  JointController& ctl = held.ctl;
  const auto& d = sim.description();
  const Eigen::VectorXd& q_j0 = held.q_j0;
  const Eigen::Vector3d p0 = sim.ground_truth().base_position;
  Eigen::Vector3d p_settled = p0;
  StandResult r;
  const int steps = static_cast<int>(std::lround(seconds / c.wbi.step));
  const int settle = static_cast<int>(std::lround(0.5 / c.wbi.step));
  const int window = static_cast<int>(std::lround(std::min(1.0, seconds / 4) / c.wbi.step));
  Eigen::Vector3d mean_early = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_late = Eigen::Vector3d::Zero();
  for (int k = 0; k < steps; ++k) {
    // a controller streaming the initial posture every tick
    ctl.submit(all_joints(d.n_joints(), ControlMode::position_direct, q_j0), sim.stamp());
    tick(sim, ctl);
    const auto& gt = sim.ground_truth();
    const Eigen::Vector3d p = gt.base_position;
    if (k == settle) {
      p_settled = p;
      r.settle_height = p.z() - p0.z();
      r.settle_horizontal = (p - p0).head<2>().norm();
    }
    if (k >= settle) {
      r.sway_horizontal = std::max(r.sway_horizontal, (p - p_settled).head<2>().norm());
    }
    if (k >= settle && k < settle + window) {
      mean_early += p / window;
    }
    if (k >= steps - window) {
      mean_late += p / window;
    }
    r.min_height = std::min(r.min_height, p.z());
    const Eigen::Quaterniond quat(gt.base_orientation[0], gt.base_orientation[1],
                                  gt.base_orientation[2], gt.base_orientation[3]);
    r.max_tilt = std::max(r.max_tilt, Eigen::AngleAxisd(quat).angle());
    r.max_joint_dev =
        std::max(r.max_joint_dev, (gt.q.tail(d.n_joints()) - q_j0).cwiseAbs().maxCoeff());
    // IMU averaged over the last 0.2 s: the quantised encoders (2^14 counts) make the
    // joint PD chatter by a fraction of a count, which the accelerometer sees.
    if (k >= steps - 200 && !sim.readings().imus.empty()) {
      r.imu_accel += sim.readings().imus[0].accel / 200.0;
    }
  }
  r.drift_height = std::abs(mean_late.z() - mean_early.z());
  r.drift_horizontal = (mean_late - mean_early).head<2>().norm();
  const auto& gt = sim.ground_truth();
  for (const auto& w : gt.contact_wrenches) {
    r.fz_total += w[2];
  }
  sim.read(sim.stamp(), std::chrono::milliseconds(1));
  for (const auto& ft : sim.readings().force_torque) {
    r.ft_z_sum += ft.wrench[2];
  }
  r.q_end = gt.q;
  r.position_end = sim.readings().position;
  return r;
}

// The humanoid on 8 contact points (corners of the foot boxes), joint PD in
// POSITION_DIRECT at the initial posture, 5 s: it must neither fall nor drift.
// The first 0.5 s it settles onto the contact springs (sag m g / 8k ≈ 1.4 mm) and
// leans by the compliance of the joint PD. Then it sways slowly (a lightly damped
// mode of the body over the ankles, whose PD damping is bounded by the foot's own
// small inertia) but must not drift: the mean base position over the last second
// equals the one over [0.5 s, 1.5 s].
TEST(SimPlant, HumanoidStandsStill) {
  const RobotConfig c = humanoid_config();
  const StandResult r = stand(c, 5.0);
  const double weight = 33.75 * 9.81;
  std::cout << "[measured] humanoid 5 s standing (h = " << c.wbi.step / c.wbi.substeps * 1e3
            << " ms): settling in 0.5 s: height " << r.settle_height * 1e3 << " mm, horizontal "
            << r.settle_horizontal * 1e3
            << " mm; drift of the mean base position [0.5, 1.5] s → [4, 5] s: height "
            << r.drift_height * 1e3 << " mm, horizontal " << r.drift_horizontal * 1e3
            << " mm; sway after 0.5 s " << r.sway_horizontal * 1e3 << " mm; max tilt "
            << r.max_tilt * 1e3 << " mrad; max joint deviation " << r.max_joint_dev * 1e3
            << " mrad; total normal force " << r.fz_total << " N (weight " << weight
            << " N); sum of foot F/T fz " << r.ft_z_sum << " N; IMU accel (mean of the last 0.2 s) "
            << r.imu_accel.transpose() << "\n";
  EXPECT_GT(r.min_height, 0.54);               // did not fall
  EXPECT_LT(std::abs(r.settle_height), 3e-3);  // contact sag
  EXPECT_LT(r.settle_horizontal, 5e-3);        // PD compliance lean
  EXPECT_LT(r.drift_height, 0.1e-3);           // no sinking
  EXPECT_LT(r.drift_horizontal, 1e-3);         // no creeping
  EXPECT_LT(r.sway_horizontal, 5e-3);
  EXPECT_LT(r.max_tilt, 15e-3);
  EXPECT_LT(r.max_joint_dev, 10e-3);
  EXPECT_NEAR(r.fz_total, weight, 0.01 * weight);
  // F/T sensors: child (foot, 0.6 kg each) on parent: contact force minus the feet's weight
  EXPECT_NEAR(r.ft_z_sum, weight - 2 * 0.6 * 9.81, 0.01 * weight);
  // IMU at rest: proper acceleration +g along the (nearly vertical) IMU z axis
  EXPECT_NEAR(r.imu_accel.z(), 9.81, 0.05);
  EXPECT_LT(r.imu_accel.head<2>().norm(), 0.1);
}

// A 30 N push on the pelvis for 0.1 s while standing with joint PD: the robot is
// pushed back, the feet take the load (the F/T sensors see it) and it stays up.
TEST(SimPlant, HumanoidSurvivesAPush) {
  RobotConfig c = humanoid_config();
  c.pushes.push_back(
      {"root_link", 1.0, 0.1, Eigen::Vector3d(-30.0, 0.0, 0.0), Eigen::Vector3d::Zero()});
  StiffSim held(c);
  SimBackend& sim = held.sim;
  JointController& ctl = held.ctl;
  const auto& d = sim.description();
  const Eigen::VectorXd& q_j0 = held.q_j0;
  const double x0 = sim.ground_truth().base_position.x();
  double min_x = x0;
  double min_z = 1.0;
  double max_ft_x = 0.0;
  for (int k = 0; k < 3000; ++k) {
    ctl.submit(all_joints(d.n_joints(), ControlMode::position_direct, q_j0), sim.stamp());
    tick(sim, ctl);
    min_x = std::min(min_x, sim.ground_truth().base_position.x());
    min_z = std::min(min_z, sim.ground_truth().base_position.z());
    if (k > 1000 && k < 1100) {
      max_ft_x = std::max(max_ft_x, std::abs(sim.readings().force_torque[0].wrench[0] +
                                             sim.readings().force_torque[1].wrench[0]));
    }
  }
  std::cout << "[measured] push 30 N × 0.1 s: base moved back " << (x0 - min_x) * 1e3
            << " mm, lowest base height " << min_z << " m, max |Σ F/T fx| " << max_ft_x << " N\n";
  EXPECT_GT(x0 - min_x, 1e-3);                              // it was pushed
  EXPECT_GT(min_z, 0.54);                                   // it did not fall
  EXPECT_GT(max_ft_x, 10.0);                                // the feet took the push
  EXPECT_LT(sim.ground_truth().nu.head<3>().norm(), 0.05);  // and it came back to rest
}

// Same seed, same commands: bit-identical trajectories and readings, with noise on.
TEST(SimPlant, SameSeedIsBitIdentical) {
  RobotConfig c = humanoid_config();
  c.wbi.encoders.position_noise = 1e-3;
  c.wbi.encoders.velocity_noise = 1e-2;
  c.imus[0].gyro_noise = 1e-2;
  c.wbi.seed = 42;
  const StandResult a = stand(c, 1.0);
  const StandResult b = stand(c, 1.0);
  ASSERT_EQ(a.q_end.size(), b.q_end.size());
  EXPECT_EQ(0, std::memcmp(a.q_end.data(), b.q_end.data(),
                           sizeof(double) * static_cast<std::size_t>(a.q_end.size())));
  c.wbi.seed = 43;
  const StandResult other = stand(c, 1.0);
  EXPECT_NE(0, std::memcmp(a.q_end.data(), other.q_end.data(),
                           sizeof(double) * static_cast<std::size_t>(a.q_end.size())));
}

}  // namespace
}  // namespace wbi::sim::test
