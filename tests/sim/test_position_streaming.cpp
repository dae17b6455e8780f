// POSITION mode under a command stream (issue 26): a controller that sends its
// target every cycle reaches it as fast as one that sends it once; a target
// that moves every cycle is tracked smoothly with a bounded lag; a watchdog
// trip followed by a stream recovers the same way. On the arm and the humanoid,
// closed loop on the simulated plant (wbi::sim), 1 kHz control.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "sim_test_common.hpp"

namespace wbi::sim::test {
namespace {

const Eigen::VectorXd kArmHome =
    (Eigen::VectorXd(7) << 0.0, 0.4, 0.0, 1.6, 0.0, 1.14, 0.0).finished();

// The arm at home; joint_1 (vertical axis: no gravity load) is the one moved.
struct Arm {
  static constexpr int kJoint = 0;
  Arm() : sim(config()), ctl(activated(sim), control()) {}

  static RobotConfig config() {
    RobotConfig c;
    c.urdf = model_path("arm7.urdf");
    for (int j = 0; j < 7; ++j) {
      c.initial_joint_positions["joint_" + std::to_string(j + 1)] = kArmHome[j];
    }
    return c;
  }
  static JointControllerConfig control() {
    JointControllerConfig cc;
    cc.watchdog_timeout = 0.1;
    return cc;  // default gains: kp = 10 × effort limit, kd = kp / 200
  }
  static const actuation::BackendDescription& activated(SimBackend& s) {
    s.configure();
    s.activate();
    return s.description();
  }
  Eigen::VectorXd posture() const { return kArmHome; }

  SimBackend sim;
  JointController ctl;
};

// The humanoid standing on the ground; its left elbow is the one moved.
struct Humanoid {
  Humanoid() : stiff(humanoid_config()), sim(stiff.sim), ctl(stiff.ctl) {
    const auto& names = sim.description().joint_names;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == "l_elbow") {
        joint = static_cast<int>(i);
      }
    }
  }
  Eigen::VectorXd posture() const { return stiff.q_j0; }

  StiffSim stiff;
  SimBackend& sim;
  JointController& ctl;
  int joint = -1;
};

int joint_of(const Arm&) { return Arm::kJoint; }
int joint_of(const Humanoid& h) { return h.joint; }

// Every joint holds `posture` in POSITION mode for 0.2 s. With `trip_first`,
// they hold it in POSITION_DIRECT and then get no command until their watchdog
// trips (0.1 s) and 0.2 s more.
template <class Robot>
void prepare(Robot& robot, bool trip_first) {
  const int n = robot.ctl.n_joints();
  const auto mode = trip_first ? ControlMode::position_direct : ControlMode::position;
  for (int k = 0; k < 200; ++k) {
    if (k == 0 || trip_first) {
      ASSERT_TRUE(robot.ctl.submit(all_joints(n, mode, robot.posture()), robot.sim.stamp()).ok);
    }
    tick(robot.sim, robot.ctl);
  }
  if (trip_first) {
    for (int k = 0; k < 300; ++k) {
      tick(robot.sim, robot.ctl);
    }
    ASSERT_EQ(robot.ctl.status().watchdog_trips, static_cast<std::uint64_t>(n));
  }
}

double joint_position(Arm& a, int j) { return a.sim.ground_truth().q[j]; }
double joint_position(Humanoid& h, int j) {
  const auto& q = h.sim.ground_truth().q;
  return q[q.size() - h.ctl.n_joints() + j];
}

// Sends POSITION `target` for the moved joint (the others keep the posture)
// once (every = 0) or every `every` ticks, and returns the time [s] at which
// the joint first comes within `tolerance` of the target (or +inf after 10 s).
template <class Robot>
double time_to_reach(Robot& robot, double target, int every, double tolerance) {
  const int n = robot.ctl.n_joints();
  const int j = joint_of(robot);
  JointCommandBatch command = all_joints(n, ControlMode::position, robot.posture());
  command.values[static_cast<std::size_t>(j)] = target;
  for (int k = 0; k < 10000; ++k) {
    if (k == 0 || (every > 0 && k % every == 0)) {
      EXPECT_TRUE(robot.ctl.submit(command, robot.sim.stamp()).ok);
    }
    tick(robot.sim, robot.ctl);
    if (std::abs(joint_position(robot, j) - target) < tolerance) {
      return (k + 1) * 1e-3;
    }
  }
  return INFINITY;
}

template <class Robot>
void expect_streams_reach_like_one_command(const char* name, double distance, double tolerance) {
  double once = 0.0;
  {
    Robot robot;
    prepare(robot, false);
    once = time_to_reach(robot, robot.posture()[joint_of(robot)] + distance, 0, tolerance);
  }
  ASSERT_TRUE(std::isfinite(once)) << name << ": a single POSITION command never got there";
  for (const bool trip_first : {false, true}) {
    for (const int every : {5, 1}) {  // 200 Hz and 1 kHz
      Robot robot;
      prepare(robot, trip_first);
      const double streamed =
          time_to_reach(robot, robot.posture()[joint_of(robot)] + distance, every, tolerance);
      std::cout << "[measured] " << name << " POSITION +" << distance << " rad"
                << (trip_first ? " after a watchdog trip" : "") << ": once " << once
                << " s, streamed at " << 1000 / every << " Hz " << streamed << " s\n";
      EXPECT_NEAR(streamed, once, 0.05 * once)
          << name << (trip_first ? " after a trip" : "") << ", streamed every " << every << " ms";
    }
  }
}

TEST(PositionStreaming, ArmStreamedTargetArrivesLikeOneCommand) {
  // 1.5 rad at the default 0.5 rad/s: a 5.6 s minimum-jerk move
  expect_streams_reach_like_one_command<Arm>("arm joint_1", 1.5, 0.01);
}

TEST(PositionStreaming, HumanoidStreamedTargetArrivesLikeOneCommand) {
  expect_streams_reach_like_one_command<Humanoid>("humanoid l_elbow", 1.0, 0.02);
}

// A target moving at v every cycle (1 kHz): after the start, the reference
// moves at v with the lag 0.6 v min_trajectory_time (joint_controller.hpp) and
// the joint follows it; the reference's acceleration stays bounded (no restart
// from rest each cycle).
template <class Robot>
void expect_ramp_tracked(const char* name, double v, double lag_bound) {
  Robot robot;
  prepare(robot, false);
  const int n = robot.ctl.n_joints();
  const int j = joint_of(robot);
  const double start = robot.posture()[j];
  JointCommandBatch command = all_joints(n, ControlMode::position, robot.posture());
  double max_reference_lag = 0.0, max_joint_lag = 0.0, max_speed_error = 0.0, max_accel = 0.0;
  double previous_speed = 0.0;
  const int ticks = 3000;
  for (int k = 0; k < ticks; ++k) {
    const double target = start + v * k * 1e-3;
    command.values[static_cast<std::size_t>(j)] = target;
    ASSERT_TRUE(robot.ctl.submit(command, robot.sim.stamp()).ok);
    tick(robot.sim, robot.ctl);
    const double speed = robot.ctl.status().velocity_reference[j];
    max_accel = std::max(max_accel, std::abs(speed - previous_speed) / 1e-3);
    previous_speed = speed;
    if (k >= 500) {  // after the start
      max_reference_lag =
          std::max(max_reference_lag, target - robot.ctl.status().position_reference[j]);
      max_joint_lag = std::max(max_joint_lag, std::abs(target - joint_position(robot, j)));
      max_speed_error = std::max(max_speed_error, std::abs(speed - v));
    }
  }
  const double expected_lag = 0.6 * v * JointControllerConfig{}.min_trajectory_time;
  std::cout << "[measured] " << name << " POSITION ramp " << v
            << " rad/s streamed at 1 kHz: reference lag " << max_reference_lag * 1e3
            << " mrad (0.6 v T_min = " << expected_lag * 1e3 << " mrad), joint lag "
            << max_joint_lag * 1e3 << " mrad, reference speed error " << max_speed_error
            << " rad/s, peak reference acceleration " << max_accel << " rad/s²\n";
  EXPECT_NEAR(max_reference_lag, expected_lag, 0.1 * expected_lag);
  EXPECT_LT(max_joint_lag, lag_bound);
  EXPECT_LT(max_speed_error, 0.01 * v);
  EXPECT_LT(max_accel, 50.0);  // a 0.3 rad/s ramp from rest in about 20 ms: ~15 rad/s²
}

TEST(PositionStreaming, ArmRampTrackedWithBoundedLag) {
  expect_ramp_tracked<Arm>("arm joint_1", 0.3, 0.02);
}

TEST(PositionStreaming, HumanoidRampTrackedWithBoundedLag) {
  expect_ramp_tracked<Humanoid>("humanoid l_elbow", 0.3, 0.03);
}

// Re-sending the current target leaves the trajectory in progress untouched:
// the references are the same, tick by tick, as without the repeats.
TEST(PositionStreaming, RepeatedTargetLeavesTheTrajectoryUntouched) {
  Arm once, streamed;
  prepare(once, false);
  prepare(streamed, false);
  JointCommandBatch command = all_joints(7, ControlMode::position, kArmHome);
  command.values[0] = 1.0;
  ASSERT_TRUE(once.ctl.submit(command, once.sim.stamp()).ok);
  for (int k = 0; k < 1000; ++k) {
    ASSERT_TRUE(streamed.ctl.submit(command, streamed.sim.stamp()).ok);
    tick(once.sim, once.ctl);
    tick(streamed.sim, streamed.ctl);
    ASSERT_EQ(once.ctl.status().position_reference[0], streamed.ctl.status().position_reference[0])
        << "tick " << k;
  }
}

}  // namespace
}  // namespace wbi::sim::test
