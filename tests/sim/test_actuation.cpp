// Joint-level control (wbi::actuation::JointController) on the simulated arm.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "sim_test_common.hpp"
#include "wbi/model/crba.hpp"
#include "wbi/model/rnea.hpp"
#include "wbi/model/urdf.hpp"

namespace wbi::sim::test {
namespace {

const Eigen::VectorXd kHome = (Eigen::VectorXd(7) << 0.0, 0.4, 0.0, 1.6, 0.0, 1.14, 0.0).finished();

RobotConfig arm_config(bool at_home) {
  RobotConfig c;
  c.urdf = model_path("arm7.urdf");
  if (at_home) {
    for (int j = 0; j < 7; ++j) {
      c.initial_joint_positions["joint_" + std::to_string(j + 1)] = kHome[j];
    }
  }
  return c;
}

// Arm gains from the joint-space inertia at home (M_jj, model library): a
// critically damped PD at ω = 40 rad/s, kp = M_jj ω², kd = 2 M_jj ω, and
// ki = kp ω / 5 (Routh: ki < kd kp / M_jj = 2 ω kp).
JointControllerConfig arm_control(double watchdog = 0.1) {
  RobotConfig c = arm_config(true);
  const model::Model m = model::load_urdf_file(c.urdf);
  model::Data data(m);
  const Eigen::MatrixXd& M = model::mass_matrix(m, data, kHome);
  JointControllerConfig cc;
  const double w = 40.0;
  for (int j = 0; j < 7; ++j) {
    PidGains g;
    g.kp = M(j, j) * w * w;
    g.kd = 2.0 * M(j, j) * w;
    g.ki = g.kp * w / 5.0;
    cc.gains.push_back(g);
  }
  cc.watchdog_timeout = watchdog;
  return cc;
}

TEST(SimActuation, ArmPositionModeReachesTargets) {
  SimBackend sim(arm_config(false));
  sim.configure();
  sim.activate();
  JointController ctl(sim.description(), arm_control());
  JointCommandBatch b = all_joints(7, ControlMode::position, kHome);
  b.reference_speeds.assign(7, 1.0);
  ASSERT_TRUE(ctl.submit(b, sim.stamp()).ok);
  double peak_ref_speed = 0.0;
  for (int k = 0; k < 4000; ++k) {  // trajectory 1.875 × 1.6 rad / 1 rad/s = 3 s, then 1 s
    tick(sim, ctl);
    peak_ref_speed =
        std::max(peak_ref_speed, ctl.status().velocity_reference.cwiseAbs().maxCoeff());
  }
  const Eigen::VectorXd q = sim.ground_truth().q;
  const double err1 = (q - kHome).cwiseAbs().maxCoeff();
  // a second target from there
  const Eigen::VectorXd target2 =
      (Eigen::VectorXd(7) << 0.8, -0.3, 0.5, 1.0, -0.6, 0.7, 1.0).finished();
  ASSERT_TRUE(ctl.submit(all_joints(7, ControlMode::position, target2), sim.stamp()).ok);
  for (int k = 0; k < 5000; ++k) {  // default 0.5 rad/s: 1.875 × 1.0 / 0.5 = 3.75 s, then 1.25 s
    tick(sim, ctl);
  }
  const double err2 = (sim.ground_truth().q - target2).cwiseAbs().maxCoeff();
  std::cout << "[measured] arm POSITION: max error at target 1 " << err1 * 1e3
            << " mrad, at target 2 " << err2 * 1e3 << " mrad, peak reference speed "
            << peak_ref_speed << " rad/s (reference 1.0)\n";
  EXPECT_LT(err1, 2e-3);
  EXPECT_LT(err2, 2e-3);
  EXPECT_LE(peak_ref_speed, 1.0 + 1e-6);
  EXPECT_GT(peak_ref_speed, 0.95);
  EXPECT_LT(sim.ground_truth().nu.cwiseAbs().maxCoeff(), 1e-2);
}

// τ = G(q) from the model library, computed on the encoder readings each tick.
// The robot config's kp/kd reach the joint controller through the backend's
// description; a joint without them keeps the default from its effort limit.
TEST(SimActuation, RobotConfigGainsAreTheJointControllersDefaults) {
  RobotConfig c = arm_config(false);
  robot_config::complete_from_urdf(c);
  c.joints.at("joint_2").kp = 123.0;
  c.joints.at("joint_2").kd = 4.5;
  c.joints.at("joint_3").kp = 50.0;  // kd not given: kp/200
  SimBackend sim(c);
  sim.configure();
  const JointController ctl(sim.description(), JointControllerConfig{});
  const auto& d = sim.description();
  const int j2 = d.joint_index("joint_2");
  const int j3 = d.joint_index("joint_3");
  const int j1 = d.joint_index("joint_1");
  EXPECT_EQ(ctl.gains(j2).kp, 123.0);
  EXPECT_EQ(ctl.gains(j2).kd, 4.5);
  EXPECT_EQ(ctl.gains(j3).kp, 50.0);
  EXPECT_EQ(ctl.gains(j3).kd, 0.25);
  const double effort = d.effort_limit[static_cast<std::size_t>(j1)];
  EXPECT_EQ(ctl.gains(j1).kp, std::isfinite(effort) ? 10.0 * effort : 100.0);
}

TEST(SimActuation, ArmTorqueModeGravityCompensationHoldsStill) {
  SimBackend sim(arm_config(true));
  sim.configure();
  sim.activate();
  JointController ctl(sim.description(), arm_control());
  const model::Model& m = sim.model();
  model::Data data(m);
  double max_dev = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const auto t = sim.stamp();
    sim.read(t, std::chrono::milliseconds(1));
    const Eigen::VectorXd& g =
        model::gravity_forces(m, data, sim.readings().position, sim.config().gravity);
    ctl.submit(all_joints(7, ControlMode::torque, g), t);
    ctl.update(t, std::chrono::milliseconds(1), sim.readings(), sim.commands());
    sim.write(t, std::chrono::milliseconds(1));
    sim.step();
    max_dev = std::max(max_dev, (sim.ground_truth().q - kHome).cwiseAbs().maxCoeff());
  }
  std::cout << "[measured] arm TORQUE = G(q), 3 s: max joint deviation " << max_dev * 1e3
            << " mrad\n";
  EXPECT_LT(max_dev, 2e-3);
  // without compensation it falls: sanity check of the test itself
  SimBackend idle(arm_config(true));
  idle.configure();
  for (int k = 0; k < 500; ++k) {
    idle.write(idle.stamp(), std::chrono::milliseconds(1));
    idle.step();
  }
  EXPECT_GT((idle.ground_truth().q - kHome).cwiseAbs().maxCoeff(), 0.05);
}

TEST(SimActuation, WatchdogTripsAndHolds) {
  SimBackend sim(arm_config(true));
  sim.configure();
  sim.activate();
  JointController ctl(sim.description(), arm_control(0.1));
  for (int k = 0; k < 300; ++k) {  // stream for 0.3 s
    ctl.submit(all_joints(7, ControlMode::position_direct, kHome), sim.stamp());
    tick(sim, ctl);
  }
  EXPECT_EQ(ctl.status().watchdog_trips, 0u);
  int trip_tick = -1;
  for (int k = 0; k < 1500; ++k) {  // silence
    tick(sim, ctl);
    if (trip_tick < 0 && ctl.status().watchdog_trips > 0) {
      trip_tick = k;
    }
  }
  EXPECT_EQ(ctl.status().watchdog_trips, 7u);
  for (auto t : ctl.status().watchdog_tripped) {
    EXPECT_EQ(t, 1);
  }
  const double dev = (sim.ground_truth().q - kHome).cwiseAbs().maxCoeff();
  std::cout << "[measured] watchdog tripped " << trip_tick << " ms after the last command "
            << "(timeout 100 ms); deviation 1.5 s later " << dev * 1e3 << " mrad\n";
  EXPECT_GE(trip_tick, 99);
  EXPECT_LE(trip_tick, 102);
  EXPECT_LT(dev, 5e-3);
  // a new command clears the trip
  ctl.submit(all_joints(7, ControlMode::position_direct, kHome), sim.stamp());
  tick(sim, ctl);
  EXPECT_EQ(ctl.status().watchdog_tripped[0], 0);
}

TEST(SimActuation, WatchdogDampsToRest) {
  SimBackend sim(arm_config(true));
  sim.configure();
  sim.activate();
  JointControllerConfig cc = arm_control(0.05);
  cc.watchdog_action = actuation::WatchdogAction::kDamp;  // τ = −kd q̇
  JointController ctl(sim.description(), cc);
  ctl.submit(all_joints(7, ControlMode::torque, Eigen::VectorXd::Zero(7)), sim.stamp());
  double max_speed = 0.0;
  for (int k = 0; k < 1000; ++k) {
    tick(sim, ctl);
    max_speed = std::max(max_speed, sim.ground_truth().nu.cwiseAbs().maxCoeff());
  }
  EXPECT_EQ(ctl.status().watchdog_trips, 7u);
  // falls under gravity, but slowly (damped): the undamped arm exceeds 1 rad/s within 0.5 s
  EXPECT_LT(max_speed, 1.0);
}

TEST(SimActuation, BadCommandsAreRejectedAndNothingIsApplied) {
  SimBackend sim(arm_config(true));
  sim.configure();
  sim.activate();
  JointController ctl(sim.description(), arm_control());
  JointCommandBatch bad;
  bad.joints = {"joint_1", "joint_9"};
  bad.modes = {ControlMode::torque, ControlMode::torque};
  bad.values = {1.0, 2.0};
  auto r = ctl.submit(bad, sim.stamp());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("unknown joint 'joint_9'"), std::string::npos) << r.error;
  bad.joints = {"joint_1", "joint_2"};
  bad.values = {1.0};
  r = ctl.submit(bad, sim.stamp());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("1 values for 2 joints"), std::string::npos) << r.error;
  bad.values = {1.0, std::nan("")};
  EXPECT_FALSE(ctl.submit(bad, sim.stamp()).ok);
  bad.joints = {"joint_1", "joint_1"};
  bad.values = {1.0, 1.0};
  EXPECT_FALSE(ctl.submit(bad, sim.stamp()).ok);
  JointCommandBatch idle_value;
  idle_value.joints = {"joint_3"};
  idle_value.values = {0.5};
  r = ctl.submit(idle_value, sim.stamp());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("IDLE"), std::string::npos) << r.error;
  tick(sim, ctl);
  for (auto mode : ctl.status().mode) {
    EXPECT_EQ(mode, ControlMode::idle);  // nothing applied
  }
  EXPECT_EQ(ctl.status().rejected_batches, 5u);
  EXPECT_EQ(ctl.status().last_error, r.error);
}

// Mode switches of several batches between two ticks all take effect in the same tick.
TEST(SimActuation, ModeSwitchesAreAtomic) {
  SimBackend sim(arm_config(true));
  sim.configure();
  sim.activate();
  JointController ctl(sim.description(), arm_control());
  JointCommandBatch a;
  a.joints = {"joint_1", "joint_2", "joint_3"};
  a.modes.assign(3, ControlMode::position_direct);
  JointCommandBatch b;
  b.joints = {"joint_4", "joint_5", "joint_6", "joint_7"};
  b.modes.assign(4, ControlMode::position);
  ASSERT_TRUE(ctl.submit(a, sim.stamp()).ok);
  for (auto mode : ctl.status().mode) {
    EXPECT_EQ(mode, ControlMode::idle);  // staged, not yet applied
  }
  ASSERT_TRUE(ctl.submit(b, sim.stamp()).ok);
  tick(sim, ctl);
  for (int j = 0; j < 7; ++j) {
    EXPECT_EQ(ctl.status().mode[static_cast<std::size_t>(j)],
              j < 3 ? ControlMode::position_direct : ControlMode::position);
  }
  // and the switched joints hold the posture they were in (bumpless)
  for (int k = 0; k < 50; ++k) {
    ctl.submit(a, sim.stamp());
    tick(sim, ctl);
  }
  EXPECT_LT((sim.ground_truth().q - kHome).cwiseAbs().maxCoeff(), 0.03);
}

// Joints by index (what the wire carries) act like joints by name, and are checked.
TEST(SimActuation, JointsByIndex) {
  SimBackend sim(arm_config(true));
  sim.configure();
  sim.activate();
  JointController ctl(sim.description(), arm_control());
  JointCommandBatch by_index;
  by_index.joint_indices = {6, 1};
  by_index.modes = {ControlMode::torque, ControlMode::position_direct};
  ASSERT_TRUE(ctl.submit(by_index, sim.stamp()).ok);
  tick(sim, ctl);
  EXPECT_EQ(ctl.status().mode[6], ControlMode::torque);
  EXPECT_EQ(ctl.status().mode[1], ControlMode::position_direct);
  EXPECT_EQ(ctl.status().mode[0], ControlMode::idle);

  by_index.joint_indices = {6, 7};
  auto r = ctl.submit(by_index, sim.stamp());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("joint index 7 out of range"), std::string::npos) << r.error;
  by_index.joint_indices = {2, 2};
  r = ctl.submit(by_index, sim.stamp());
  EXPECT_NE(r.error.find("'joint_3' appears twice"), std::string::npos) << r.error;
  by_index.joint_indices = {2, 3};
  by_index.joints = {"joint_3", "joint_4"};
  r = ctl.submit(by_index, sim.stamp());
  EXPECT_NE(r.error.find("both by name and by index"), std::string::npos) << r.error;
}

// PWM through the DC-motor model: τ = k_t (V pwm − k_e q̇)/R, k_t = k_e = effort·R/V.
TEST(SimActuation, PwmDrivesTheMotorModel) {
  SimBackend sim(arm_config(true));
  sim.configure();
  sim.activate();
  JointController ctl(sim.description(), arm_control());
  // joint_1 (vertical axis: no gravity torque) in PWM, the others hold the posture
  JointCommandBatch b = all_joints(7, ControlMode::position_direct, kHome);
  b.modes[0] = ControlMode::pwm;
  b.values[0] = 0.25;
  for (int k = 0; k < 200; ++k) {
    ctl.submit(b, sim.stamp());
    tick(sim, ctl);
  }
  const double kt = 120.0 * 1.0 / 24.0;
  const double dq = sim.ground_truth().nu[0];
  const double expected = kt * (24.0 * 0.25 - kt * dq) / 1.0;
  std::cout << "[measured] PWM 0.25 on joint_1 for 0.2 s: q̇ = " << dq
            << " rad/s, τ = " << sim.ground_truth().tau_actuator[0] << " N·m\n";
  EXPECT_GT(dq, 0.1);
  // (q̇ of the last substep differs slightly from the one after it)
  EXPECT_NEAR(sim.ground_truth().tau_actuator[0], expected, 0.3);
  sim.read(sim.stamp(), std::chrono::milliseconds(1));
  EXPECT_NEAR(sim.readings().pwm[0], 0.25, 1e-9);
}

}  // namespace
}  // namespace wbi::sim::test
