// The legged base estimator (IMU + both feet) against the simulator's ground
// truth: the humanoid stands and sways under joint position control (no DDS:
// wbi::sim and the joint controller in the loop, the estimator fed what the
// component would get: quantised encoders differentiated by the backward
// difference, the IMU, the feet's F/T). Then a foot is unloaded, moved and put
// down again (anchors re-set), and bad input is named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <wbi/estimation/estimator_factory.hpp>
#include <wbi/estimator/base_estimator.hpp>
#include <wbi/estimator/legged_base_estimator.hpp>
#include <wbi/model/algorithms.hpp>

#include "allocation_counter.hpp"
#include "sim_test_common.hpp"

namespace {

using wbi::estimator::LeggedBaseEstimator;
using wbi::estimator::LeggedBaseOptions;
using namespace wbi::sim::test;
using wbi::robot_config::RobotConfig;
using wbi::sim::SimBackend;

LeggedBaseOptions humanoid_options() {
  LeggedBaseOptions options;
  options.imu_frame = "imu_frame";
  options.force_frames = {{{"l_foot"}, {"r_foot"}}};  // the F/T sensors' child links
  return options;
}

struct Errors {
  double position_max = 0.0;         // ‖p̂_B − p_B‖ [m]
  double orientation_max = 0.0;      // angle of R̂_Bᵀ R_B [rad]
  double linear_velocity_rms = 0.0;  // [m/s]
  double linear_velocity_max = 0.0;
  double angular_velocity_max = 0.0;     // [rad/s]
  double fixed_link_velocity_rms = 0.0;  // the l_sole fixed-link estimate, for comparison
  double sway = 0.0;                     // the largest lateral base excursion (ground truth) [m]
  long allocations = 0;                  // in the estimator's updates after the first
};

// `seconds` of standing, the pelvis swaying sideways by hip and ankle roll
// (amplitude `roll` rad at 0.5 Hz), errors after the first `settle` seconds.
Errors stand_and_sway(double seconds, double roll, const LeggedBaseOptions& options,
                      double settle = 0.3) {
  const RobotConfig config = humanoid_config();
  StiffSim held(config);
  SimBackend& sim = held.sim;
  JointController& ctl = held.ctl;
  const auto& d = sim.description();
  const int n = d.n_joints();
  const Eigen::VectorXd q0 = sim.ground_truth().q.tail(n);

  LeggedBaseEstimator legged(config.urdf, d.joint_names, options);
  const auto& model = legged.model();
  const Eigen::Vector3d p0 = sim.ground_truth().base_position;
  wbi::estimator::FixedLinkBaseEstimator fixed_link(config.urdf, d.joint_names, "l_sole",
                                                    Eigen::Matrix4d::Identity());
  auto derivative = wbi::estimation::make_estimator("backward-difference", n, {{"cutoff", 50.0}});

  Eigen::VectorXd target = q0;
  const int hip_roll[2] = {model.joint_id("l_hip_roll"), model.joint_id("r_hip_roll")};
  const int ankle_roll[2] = {model.joint_id("l_ankle_roll"), model.joint_id("r_ankle_roll")};
  Errors e;
  double squared = 0.0;
  double squared_fixed = 0.0;
  int samples = 0;
  Eigen::Matrix<double, 3, 2> forces;
  Eigen::VectorXd truth_q = sim.ground_truth().q;
  Eigen::VectorXd truth_nu = sim.ground_truth().nu;
  const int steps = static_cast<int>(std::lround(seconds / config.wbi.step));
  for (int k = 0; k < steps; ++k) {
    const double t = k * config.wbi.step;
    const double s = roll * std::sin(2.0 * M_PI * 0.5 * t) * std::min(1.0, t);  // fade in
    for (int foot = 0; foot < 2; ++foot) {
      const double axis = foot == 0 ? 1.0 : -1.0;  // the right leg's roll axes are mirrored
      target[hip_roll[foot]] = q0[hip_roll[foot]] + axis * s;
      target[ankle_roll[foot]] = q0[ankle_roll[foot]] - axis * s;
    }
    ctl.submit(all_joints(n, ControlMode::position_direct, target), sim.stamp());
    truth_q = sim.ground_truth().q;  // the state the sensors read before the step
    truth_nu = sim.ground_truth().nu;
    tick(sim, ctl);
    const auto& r = sim.readings();
    derivative->update(r.joint_stamp.count(), r.position);
    const auto& imu = r.imus[0];
    for (int foot = 0; foot < 2; ++foot) {
      forces.col(foot) = r.force_torque[static_cast<std::size_t>(foot)].wrench.head<3>();
    }
    wbi::estimator::ImuInput imu_input;
    imu_input.orientation = Eigen::Quaterniond(imu.orientation[0], imu.orientation[1],
                                               imu.orientation[2], imu.orientation[3]);
    imu_input.gyro = imu.gyro;
    imu_input.accelerometer = imu.accel;
    const long before = wbi::test::allocation_count();
    const auto& estimate = legged.update(r.joint_stamp.count(), r.position, derivative->velocity(),
                                         derivative->acceleration(), imu_input, forces);
    if (k > 0) {
      e.allocations += wbi::test::allocation_count() - before;
    }
    if (k == 0) {  // the fixed-link estimate starts where the legged one does
      fixed_link = wbi::estimator::FixedLinkBaseEstimator(config.urdf, d.joint_names, "l_sole",
                                                          estimate.world_H_base);
    }
    const auto& fixed =
        fixed_link.update(r.position, derivative->velocity(), derivative->acceleration());

    if (t < settle) {
      continue;
    }
    const Eigen::Vector3d p = truth_q.head<3>();
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(truth_q[3], truth_q[4], truth_q[5], truth_q[6]).toRotationMatrix();
    e.position_max =
        std::max(e.position_max, (estimate.world_H_base.topRightCorner<3, 1>() - p).norm());
    e.orientation_max = std::max(
        e.orientation_max,
        Eigen::AngleAxisd(estimate.world_H_base.topLeftCorner<3, 3>().transpose() * R).angle());
    const double v_error = (estimate.velocity.head<3>() - truth_nu.head<3>()).norm();
    squared += v_error * v_error;
    const double v_fixed = (fixed.velocity.head<3>() - truth_nu.head<3>()).norm();
    squared_fixed += v_fixed * v_fixed;
    ++samples;
    e.linear_velocity_max = std::max(e.linear_velocity_max, v_error);
    e.angular_velocity_max = std::max(
        e.angular_velocity_max, (estimate.velocity.tail<3>() - truth_nu.segment<3>(3)).norm());
    e.sway = std::max(e.sway, std::abs(p.y() - p0.y()));
  }
  e.linear_velocity_rms = std::sqrt(squared / samples);
  e.fixed_link_velocity_rms = std::sqrt(squared_fixed / samples);
  return e;
}

}  // namespace

namespace {

// Standing and swaying (±8 cm of pelvis), both feet on the ground, the load moving
// from foot to foot (each foot unloads at the extremes: anchors re-set). Tolerances:
// position 5 mm (the contact springs give 1.4 mm per foot under half the weight and
// 2.8 mm under all of it, which the kinematics cannot see); orientation 1 mrad (the
// IMU's, exact in the sim); linear velocity from the kinematics alone 3 cm/s rms (the
// quantised encoders differentiated: 0.38 mrad steps at 1 kHz through a 50 Hz
// low-pass, times ~0.5 m of leg), with the accelerometer blended in (τ = 0.05 s,
// the default) 5 mm/s rms.
TEST(LeggedBaseEstimator, TracksTheGroundTruthWhileSwaying) {
  auto kinematic = humanoid_options();
  kinematic.velocity_time_constant = 0.0;
  const Errors k = stand_and_sway(4.0, 0.08, kinematic);
  const Errors e = stand_and_sway(4.0, 0.08, humanoid_options());
  std::printf(
      "[measured] sway %.3f m: position max %.2e m, orientation max %.2e rad, angular velocity "
      "max %.2e rad/s; linear velocity rms %.2e m/s (max %.2e) with the accelerometer, %.2e m/s "
      "(max %.2e) from the kinematics alone; fixed-link (l_sole) %.2e m/s\n",
      e.sway, e.position_max, e.orientation_max, e.angular_velocity_max, e.linear_velocity_rms,
      e.linear_velocity_max, k.linear_velocity_rms, k.linear_velocity_max,
      e.fixed_link_velocity_rms);
  EXPECT_GT(e.sway, 0.05) << "m: the robot did not sway; the test is void";
  EXPECT_LT(e.position_max, 5e-3);
  EXPECT_LT(e.orientation_max, 1e-3);
  EXPECT_LT(e.angular_velocity_max, 1e-6);  // the gyro on the base link: exact
  EXPECT_LT(k.linear_velocity_rms, 0.03);
  EXPECT_LT(e.linear_velocity_rms, 0.005);
  EXPECT_LT(e.linear_velocity_max, 0.015);
  EXPECT_LT(e.linear_velocity_rms, 0.5 * k.linear_velocity_rms) << "the blend does not help";
  EXPECT_EQ(e.allocations, 0) << "heap allocations in update()";
}

}  // namespace

namespace {

// Synthetic inputs: a level IMU, both feet's forces in their (level) sensor frames.
struct Stepper {
  LeggedBaseEstimator estimator;
  Eigen::VectorXd q;
  std::int64_t stamp_ns = 0;

  explicit Stepper(const LeggedBaseOptions& options)
      : estimator(wbi::test::project_model("humanoid.urdf").string(), joint_names(), options),
        q(Eigen::VectorXd::Zero(estimator.model().n_joints)) {
    for (const char* leg : {"l_", "r_"}) {  // knees bent, as the sim's humanoid stands
      set(std::string(leg) + "hip_pitch", -0.3);
      set(std::string(leg) + "knee", 0.6);
      set(std::string(leg) + "ankle_pitch", -0.3);
    }
  }
  static std::vector<std::string> joint_names() {
    const auto model = wbi::model::load_urdf_file(wbi::test::project_model("humanoid.urdf"));
    return {model.joint_name.begin(), model.joint_name.end()};
  }
  void set(const std::string& joint, double value) { q[estimator.model().joint_id(joint)] = value; }
  Eigen::Vector3d base(double left_force, double right_force) {
    Eigen::Matrix<double, 3, 2> forces = Eigen::Matrix<double, 3, 2>::Zero();
    forces.row(2) << left_force, right_force;
    stamp_ns += 1'000'000;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(q.size());
    return estimator.update(stamp_ns, q, zero, zero, wbi::estimator::ImuInput{}, forces)
        .world_H_base.topRightCorner<3, 1>();
  }
};

// A foot unloaded, moved and put down again is anchored where it landed; then the
// other foot is lifted and the base follows the newly anchored foot: no jump anywhere.
TEST(LeggedBaseEstimator, AFootPutDownElsewhereIsAnchoredWhereItLanded) {
  auto options = humanoid_options();
  options.flat_ground = false;
  Stepper s(options);
  const Eigen::Vector3d p0 = s.base(160.0, 160.0);
  EXPECT_NEAR(s.estimator.anchor(0).z(), 0.0, 1e-12);  // started with the soles on the ground
  EXPECT_NEAR(s.estimator.anchor(1).z(), 0.0, 1e-12);
  const Eigen::Vector3d right_before = s.estimator.anchor(1);

  // Unload the right foot (below unload_force) and swing the leg out: the base stays.
  EXPECT_TRUE(p0.isApprox(s.base(320.0, 10.0), 1e-12));
  EXPECT_FALSE(s.estimator.loaded(1));
  s.set("r_hip_roll", 0.1);  // its axis is −x: the foot moves to the right (−y)
  EXPECT_TRUE(p0.isApprox(s.base(320.0, 10.0), 1e-12));
  EXPECT_TRUE(p0.isApprox(s.base(320.0, 30.0), 1e-12));  // 30 N < load_force: still unloaded
  EXPECT_FALSE(s.estimator.loaded(1));

  // Put it down: re-anchored where the kinematics put it now.
  EXPECT_TRUE(p0.isApprox(s.base(160.0, 160.0), 1e-12));
  EXPECT_TRUE(s.estimator.loaded(1));
  const Eigen::Vector3d right_after = s.estimator.anchor(1);
  EXPECT_LT(right_after.y(), right_before.y() - 0.02) << "the right foot moved outwards";
  EXPECT_TRUE(p0.isApprox(s.base(160.0, 30.0), 1e-12));  // 30 N > unload_force: still loaded
  EXPECT_TRUE(s.estimator.loaded(1));

  // Lift the left foot and bend its knee: the base now stands on the right foot alone.
  s.base(0.0, 320.0);
  s.set("l_knee", 1.0);
  EXPECT_TRUE(p0.isApprox(s.base(0.0, 320.0), 1e-12));
  EXPECT_TRUE(s.estimator.anchor(1).isApprox(right_after, 1e-12));
}

// On flat ground a foot put down keeps its anchor's height.
TEST(LeggedBaseEstimator, FlatGroundKeepsTheHeightOfAFootPutDown) {
  Stepper s(humanoid_options());
  s.base(160.0, 160.0);
  s.base(320.0, 0.0);
  s.set("r_knee", 0.8);  // the right foot up by a few cm
  s.base(320.0, 0.0);
  s.base(160.0, 160.0);
  EXPECT_NEAR(s.estimator.anchor(1).z(), 0.0, 1e-12);
}

// A foot on two F/T sensors (iCub 3's front and rear plates) carries their sum:
// 25 N on each of the left foot's sensors loads it (50 N > load_force 40 N),
// which neither sensor alone would.
TEST(LeggedBaseEstimator, AFootOnTwoSensorsCarriesTheirSum) {
  auto options = humanoid_options();
  options.force_frames[0] = {"l_foot", "l_foot"};  // the left foot's two sensors
  Stepper s(options);
  ASSERT_EQ(s.estimator.force_sensors(), 3);
  Eigen::Matrix3Xd forces = Eigen::Matrix3Xd::Zero(3, 3);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s.q.size());
  auto update = [&](double left_front, double left_rear, double right) {
    forces.row(2) << left_front, left_rear, right;
    s.stamp_ns += 1'000'000;
    s.estimator.update(s.stamp_ns, s.q, zero, zero, wbi::estimator::ImuInput{}, forces);
  };
  update(25.0, 25.0, 200.0);
  EXPECT_TRUE(s.estimator.loaded(0)) << "50 N on two sensors";
  update(5.0, 10.0, 300.0);
  EXPECT_FALSE(s.estimator.loaded(0)) << "15 N < unload_force";
  update(25.0, 0.0, 300.0);
  EXPECT_FALSE(s.estimator.loaded(0)) << "25 N < load_force";
  update(25.0, 25.0, 300.0);
  EXPECT_TRUE(s.estimator.loaded(0));
  // Fewer forces than sensors: named.
  const Eigen::Matrix<double, 3, 2> two = Eigen::Matrix<double, 3, 2>::Zero();
  EXPECT_THROW(
      s.estimator.update(s.stamp_ns + 1'000'000, s.q, zero, zero, wbi::estimator::ImuInput{}, two),
      std::invalid_argument);
}

TEST(LeggedBaseEstimator, BadInputIsNamed) {
  const auto urdf = wbi::test::project_model("humanoid.urdf").string();
  const auto joints = Stepper::joint_names();
  const auto message = [&](const LeggedBaseOptions& options) -> std::string {
    try {
      LeggedBaseEstimator estimator(urdf, joints, options);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  auto options = humanoid_options();
  options.feet[1] = "r_shoe";
  EXPECT_NE(message(options).find("unknown foot frame 'r_shoe'"), std::string::npos);
  options = humanoid_options();
  options.imu_frame = "head_imu";
  EXPECT_NE(message(options).find("unknown IMU frame 'head_imu'"), std::string::npos);
  options = humanoid_options();
  options.unload_force = 50.0;
  EXPECT_NE(message(options).find("unload_force <= load_force"), std::string::npos);
  options = humanoid_options();
  options.velocity_time_constant = -1.0;
  EXPECT_NE(message(options).find("velocity_time_constant"), std::string::npos);

  Stepper s(humanoid_options());
  const Eigen::Vector3d before = s.base(160.0, 160.0);
  EXPECT_TRUE(s.base(std::nan(""), 160.0).isApprox(before, 1e-12)) << "a NaN force is ignored";
  s.set("l_knee", std::nan(""));
  EXPECT_TRUE(s.base(160.0, 160.0).isApprox(before, 1e-12)) << "a NaN joint is ignored";
  const Eigen::VectorXd short_q = Eigen::VectorXd::Zero(3);
  try {
    s.estimator.update(0, short_q, short_q, short_q, {}, Eigen::Matrix<double, 3, 2>::Zero());
    ADD_FAILURE() << "no error for 3 joint positions";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("must have size 30"), std::string::npos) << e.what();
  }
}

}  // namespace
