// The whole-body interface over DDS, against a robot peer made of real DDS
// endpoints in this process: init names what is missing, reads map the
// robot's joint order to the controller's, stale data is refused, commands
// and parameters reach the robot with the robot's joint indices, and the
// model over a subset of joints agrees with the full model.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include <wbi/model/algorithms.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "arm_peer.hpp"

namespace {

using namespace wbi::test;

// init() waits for the sensor samples only when the controller declared it
// reads them (read_sensors); else they are subscribed to at the first read.
TEST(DdsInterface, InitNamesEveryMissingComponent) {
  for (const bool read_sensors : {false, true}) {
    wbi::DdsInterfaceOptions options = arm_options("absent");
    options.read_sensors = read_sensors;
    auto robot = wbi::make_dds_interface(options);
    robot->add_joints({"joint_1"});
    try {
      robot->init(300ms);
      FAIL() << "init succeeded without a robot";
    } catch (const wbi::TimeoutError& e) {
      const std::string text = e.what();
      EXPECT_NE(text.find("robot description"), std::string::npos) << text;
      EXPECT_EQ(text.find("sensor samples on wbi/absent/sensors") != std::string::npos,
                read_sensors)
          << text;
      EXPECT_NE(text.find("state estimates"), std::string::npos) << text;
      EXPECT_NE(text.find("actuator component"), std::string::npos) << text;
    }
  }
}

TEST(DdsInterface, BadOptionsAndJointsAreNamed) {
  wbi::DdsInterfaceOptions options = arm_options("");
  EXPECT_THROW(wbi::make_dds_interface(options), wbi::Error);
  options = arm_options("arm");
  options.urdf.clear();
  EXPECT_THROW(wbi::make_dds_interface(options), wbi::Error);

  ArmPeer peer("arm_bad");
  auto robot = wbi::make_dds_interface(arm_options("arm_bad"));
  EXPECT_THROW(robot->add_joints({"joint_1", "joint_1"}), wbi::Error);
  robot->add_joints({"joint_9"});
  try {
    robot->init(10s);
    FAIL() << "unknown joint accepted";
  } catch (const wbi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("'joint_9' is not a joint of robot 'arm_bad'"),
              std::string::npos)
        << e.what();
  }
  Eigen::VectorXd q(1);
  EXPECT_THROW(robot->read_sensors(wbi::SensorKind::encoder_position, q), wbi::Error);
}

TEST(DdsInterface, ReadsFollowTheControllersJointOrder) {
  ArmPeer peer("arm_read");
  auto robot = wbi::make_dds_interface(arm_options("arm_read"));
  robot->add_joints({"joint_4", "joint_1", "joint_6"});
  robot->init(10s);
  ASSERT_EQ(robot->dofs(), 3);

  Eigen::VectorXd q(3);
  const wbi::Stamp stamp =
      robot->read_sensors(wbi::SensorKind::encoder_position, q, wbi::ReadMode::blocking);
  EXPECT_DOUBLE_EQ(q[0], arm_position(3));
  EXPECT_DOUBLE_EQ(q[1], arm_position(0));
  EXPECT_DOUBLE_EQ(q[2], arm_position(5));
  EXPECT_GE(stamp.age_s, 0.0);

  Eigen::VectorXd dq(3);
  robot->read_estimates(wbi::EstimateKind::joint_velocity, dq, wbi::ReadMode::blocking);
  EXPECT_DOUBLE_EQ(dq[0], arm_velocity(3));
  EXPECT_DOUBLE_EQ(dq[2], arm_velocity(5));
  Eigen::VectorXd one(1);
  robot->read_estimate(wbi::EstimateKind::joint_velocity, 1, one);
  EXPECT_DOUBLE_EQ(one[0], arm_velocity(0));

  wbi::Transform world_H_base;
  robot->read_base_pose(world_H_base);
  EXPECT_DOUBLE_EQ(world_H_base(2, 3), 0.25);
  EXPECT_TRUE((world_H_base.topLeftCorner<3, 3>().isIdentity()));

  // Blocking reads return a newer sample each time.
  const auto first =
      robot->read_sensors(wbi::SensorKind::encoder_position, q, wbi::ReadMode::blocking);
  const auto second =
      robot->read_sensors(wbi::SensorKind::encoder_position, q, wbi::ReadMode::blocking);
  EXPECT_GT(second.seq, first.seq);

  Eigen::VectorXd wrong(2);
  try {
    robot->read_sensors(wbi::SensorKind::encoder_position, wrong);
    FAIL() << "wrong size accepted";
  } catch (const wbi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("has size 2, expected 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(robot->read_sensors(wbi::SensorKind::joint_torque, q), wbi::Error);  // none sent
}

// A proxy that reads only the state never takes a sensor sample: it
// subscribes to them at the first read of a sensor kind, which then waits
// for the first sample.
TEST(DdsInterface, SensorSamplesAreSubscribedAtTheirFirstRead) {
  ArmPeer peer("arm_lazy");
  auto robot = wbi::make_dds_interface(arm_options("arm_lazy"));
  robot->add_joints({"joint_2", "joint_5"});
  robot->init(10s);
  wbi::RobotState state;
  robot->state().read_robot_state(state, wbi::ReadMode::blocking);
  EXPECT_EQ(peer.sensor_writer().matched(), 0);

  Eigen::VectorXd q(2);
  robot->read_sensors(wbi::SensorKind::encoder_position,
                      q);  // latest: the first sample, waited for
  EXPECT_DOUBLE_EQ(q[0], arm_position(1));
  EXPECT_DOUBLE_EQ(q[1], arm_position(4));
  EXPECT_TRUE(peer.sensor_writer().wait_for_subscribers(1, 10s));
}

// Every kind of the enum, read whole: each is answered with the estimator's
// values, or (F/T estimates missing from the state) refused with wbi::Error
// naming the kind, never an exception of another type.
TEST(DdsInterface, EveryEstimateKindIsAnswered) {
  ArmPeer peer("arm_kinds", 2);
  auto robot = wbi::make_dds_interface(arm_options("arm_kinds"));
  robot->add_joints({"joint_2", "joint_5"});
  robot->init(10s);
  const auto last = static_cast<int>(wbi::EstimateKind::external_wrench);
  for (int k = 0; k <= last; ++k) {
    const auto kind = static_cast<wbi::EstimateKind>(k);
    const int count = k <= static_cast<int>(wbi::EstimateKind::joint_torque) ? 2
                      : kind == wbi::EstimateKind::force_torque              ? 2
                                                                             : 1;
    ASSERT_EQ(count, wbi::estimate_count(kind, 2, 2, 1)) << k;
    Eigen::VectorXd values = Eigen::VectorXd::Constant(count * wbi::estimate_width(kind), -99.0);
    ASSERT_NO_THROW(robot->read_estimates(kind, values, wbi::ReadMode::blocking)) << k;
    EXPECT_TRUE(values.allFinite()) << k;
    EXPECT_FALSE((values.array() == -99.0).any()) << "kind " << k << " left values unwritten";
  }
  Eigen::VectorXd wrenches(12);
  robot->read_estimates(wbi::EstimateKind::force_torque, wrenches);
  EXPECT_DOUBLE_EQ(wrenches[2], arm_wrench(0));
  EXPECT_DOUBLE_EQ(wrenches[9], -arm_wrench(1));
  ASSERT_EQ(robot->external_wrench_links(), wbi::IdList{kArmWrenchLink});
  Eigen::VectorXd external(6);
  robot->read_estimate(wbi::EstimateKind::external_wrench, 0, external);
  EXPECT_DOUBLE_EQ(external[2], kArmExternalForce);
  EXPECT_DOUBLE_EQ(external[4], -kArmExternalForce);
  Eigen::VectorXd velocity(2);
  robot->read_estimates(wbi::EstimateKind::joint_velocity, velocity);
  EXPECT_DOUBLE_EQ(velocity[1], arm_velocity(4));
}

TEST(DdsInterface, ForceTorqueEstimatesMissingFromTheStateAreNamed) {
  ArmPeer peer("arm_no_ft_state", 2, /*state_without_force_torque=*/true);
  auto robot = wbi::make_dds_interface(arm_options("arm_no_ft_state"));
  robot->add_joints({"joint_1"});
  robot->init(10s);
  Eigen::VectorXd wrenches(12);
  try {
    robot->read_estimates(wbi::EstimateKind::force_torque, wrenches, wbi::ReadMode::blocking);
    FAIL() << "no error";
  } catch (const wbi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("force_torque estimates"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("carries 0 of its 2 F/T sensors"), std::string::npos)
        << e.what();
  }
  robot->read_sensors(wbi::SensorKind::force_torque, wrenches);  // the raw readings are there
  EXPECT_DOUBLE_EQ(wrenches[8], arm_wrench(1));
}

// An interface to `robot`'s joint_2 whose samples are stale after 50 ms, initialized.
std::unique_ptr<wbi::WholeBodyInterface> quickly_stale_joint_2(const std::string& robot_name) {
  auto options = arm_options(robot_name);
  options.max_age_s = 0.05;
  auto robot = wbi::make_dds_interface(options);
  robot->add_joints({"joint_2"});
  robot->init(10s);
  return robot;
}

TEST(DdsInterface, StaleDataIsRefused) {
  ArmPeer peer("arm_stale");
  auto robot = quickly_stale_joint_2("arm_stale");
  Eigen::VectorXd q(1);
  robot->read_sensors(wbi::SensorKind::encoder_position, q, wbi::ReadMode::blocking);
  robot->read_estimates(wbi::EstimateKind::joint_position, q, wbi::ReadMode::blocking);
  peer.stop();
  // Once the robot is silent, the newest sample only ages: latest reads of
  // both streams fail after max_age (samples still in flight when the peer
  // stopped are fresh when they arrive: the loop reads past them).
  const auto refused = [&](const auto& read) {
    const auto deadline = std::chrono::steady_clock::now() + 5s;
    while (std::chrono::steady_clock::now() < deadline) {
      try {
        read();
        std::this_thread::sleep_for(10ms);  // polling an ageing sample: there is no event to await
      } catch (const wbi::StaleDataError& e) {
        EXPECT_NE(std::string(e.what()).find("old (limit"), std::string::npos) << e.what();
        return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(refused([&] { robot->read_sensors(wbi::SensorKind::encoder_position, q); }));
  EXPECT_TRUE(refused([&] { robot->read_estimates(wbi::EstimateKind::joint_position, q); }));
}

// A lockstep robot waits at tick 0 for its answer: the sample init() waited
// for is read however old it is (a secured start can take longer than
// max_age_s after it arrived) until a command answers it; then it is stale.
TEST(DdsInterface, ALockstepRobotsFirstSampleIsReadUntilAnswered) {
  ArmPeer peer("arm_lockstep", 0, false, /*lockstep=*/true);
  auto robot = quickly_stale_joint_2("arm_lockstep");
  Eigen::VectorXd q(1);
  wbi::Stamp stamp;
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  do {
    stamp = robot->state().read_estimates(wbi::EstimateKind::joint_position, q);
    std::this_thread::sleep_for(10ms);  // polling an ageing sample: there is no event to await
  } while (stamp.age_s <= 0.1 && std::chrono::steady_clock::now() < deadline);
  EXPECT_GT(stamp.age_s, 0.1);  // twice max_age_s
  EXPECT_EQ(stamp.seq, 0u);
  EXPECT_DOUBLE_EQ(q[0], arm_position(1));
  robot->actuators().set_control_mode(wbi::ControlMode::torque);  // answers no tick
  EXPECT_NO_THROW(robot->state().read_estimates(wbi::EstimateKind::joint_position, q));
  robot->actuators().set_control_reference(Eigen::VectorXd::Zero(1));  // answers tick 0
  EXPECT_THROW(robot->state().read_estimates(wbi::EstimateKind::joint_position, q),
               wbi::StaleDataError);
}

// One call, one estimate: every field of the RobotState comes from the sample
// whose number it carries (the peer writes it into ddq, the base velocity and
// the base x), while the peer publishes new samples during the reads.
TEST(DdsInterface, TheRobotStateIsOneEstimate) {
  ArmPeer peer("arm_state");
  auto robot = wbi::make_dds_interface(arm_options("arm_state"));
  robot->add_joints({"joint_3", "joint_1"});
  robot->init(10s);
  wbi::RobotState state;  // sized by the first read
  std::uint64_t previous = 0;
  for (int k = 0; k < 200; ++k) {
    const auto mode = k % 2 == 0 ? wbi::ReadMode::blocking : wbi::ReadMode::latest;
    const wbi::Stamp stamp = robot->state().read_robot_state(state, mode);
    const auto seq = static_cast<double>(stamp.seq);
    ASSERT_EQ(state.q.size(), 2);
    EXPECT_EQ(state.stamp.seq, stamp.seq);
    EXPECT_DOUBLE_EQ(state.q[0], arm_position(2));
    EXPECT_DOUBLE_EQ(state.q[1], arm_position(0));
    EXPECT_DOUBLE_EQ(state.dq[0], arm_velocity(2));
    EXPECT_TRUE((state.ddq.array() == seq).all()) << k;
    EXPECT_DOUBLE_EQ(state.base_velocity[0], seq) << k;
    EXPECT_DOUBLE_EQ(state.world_H_base(0, 3), seq) << k;
    EXPECT_DOUBLE_EQ(state.world_H_base(2, 3), 0.25);
    if (mode == wbi::ReadMode::blocking && k > 0) {  // the first: the newest, init()'s included
      EXPECT_GT(stamp.seq, previous) << "a blocking read returns a newer estimate";
    }
    previous = stamp.seq;
  }
}

TEST(DdsInterface, ARobotStateReadWaitsABoundedTime) {
  ArmPeer peer("arm_state_timeout");
  auto options = arm_options("arm_state_timeout");
  options.blocking_read_timeout = 200ms;
  options.max_age_s = 60.0;  // this test is about blocking reads, not ageing samples
  auto robot = wbi::make_dds_interface(options);
  robot->add_joints({"joint_1"});
  robot->init(10s);
  wbi::RobotState state(1);
  robot->read_robot_state(state, wbi::ReadMode::blocking);
  peer.stop();
  // Estimates the peer sent just before it stopped may still be in flight
  // (CI saw one arrive after this point): take them all first, so that the
  // blocking read waits for one that never comes.
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (state.stamp.seq != peer.last_published_seq() &&
         std::chrono::steady_clock::now() < deadline) {
    robot->read_robot_state(state, wbi::ReadMode::latest);
    std::this_thread::yield();
  }
  ASSERT_EQ(state.stamp.seq, peer.last_published_seq()) << "the peer's last estimate never came";
  try {
    robot->read_robot_state(state, wbi::ReadMode::blocking);
    FAIL() << "a blocking read returned without a new estimate";
  } catch (const wbi::TimeoutError& e) {
    EXPECT_NE(std::string(e.what()).find("state estimates of robot 'arm_state_timeout'"),
              std::string::npos)
        << e.what();
  }
}

// Each element is an object of its own: code that needs only the model takes a
// wbi::Model&, and the elements refuse use before init() like the flat API.
TEST(DdsInterface, ElementsAreObjectsOfTheirOwn) {
  ArmPeer peer("arm_elements");
  auto robot = wbi::make_dds_interface(arm_options("arm_elements"));
  robot->add_joints({"joint_1", "joint_2"});
  EXPECT_EQ(robot->dofs(), 2);  // the controlled list is known before init()
  EXPECT_THROW(robot->model(), wbi::Error);
  EXPECT_THROW(robot->actuators(), wbi::Error);
  robot->init(10s);
  const auto gravity_of = [](wbi::Model& model, const Eigen::VectorXd& q) {
    Eigen::VectorXd g(6 + model.dofs());
    model.gravity_forces(q, wbi::Transform::Identity(), Eigen::Vector3d(0, 0, -9.81), g);
    return g;
  };
  const Eigen::VectorXd q = Eigen::Vector2d(0.3, -0.6);
  Eigen::VectorXd flat(8);
  robot->gravity_forces(q, wbi::Transform::Identity(), Eigen::Vector3d(0, 0, -9.81), flat);
  EXPECT_TRUE(gravity_of(robot->model(), q).isApprox(flat));
  EXPECT_EQ(robot->model().joint_list(), robot->joint_list());
  EXPECT_EQ(&robot->state(), &robot->state());
}

TEST(DdsInterface, CommandsCarryTheRobotsJointIndices) {
  ArmPeer peer("arm_cmd");
  auto robot = wbi::make_dds_interface(arm_options("arm_cmd"));
  robot->add_joints({"joint_7", "joint_3"});
  robot->init(10s);

  robot->set_control_mode(wbi::ControlMode::torque);
  Eigen::Vector2d tau(1.5, -2.5);
  robot->set_control_reference(tau);
  wbi::dds::Received<wbi::msg::ActuatorCommand> command;
  ASSERT_TRUE(peer.commands().wait_newer(command, 1, 5s));
  const auto& c = command.sample;
  EXPECT_EQ(c.controller(), "test_controller");
  ASSERT_EQ(c.joints().size(), 2u);
  EXPECT_EQ(c.joints()[0], 6);
  EXPECT_EQ(c.joints()[1], 2);
  EXPECT_EQ(c.modes()[0], wbi::msg::ControlMode::TORQUE);
  EXPECT_DOUBLE_EQ(c.references()[0], 1.5);
  EXPECT_DOUBLE_EQ(c.references()[1], -2.5);

  // Switching one joint to position control holds it where it is measured.
  robot->set_control_mode(wbi::ControlMode::position, 1);
  ASSERT_TRUE(peer.commands().wait_newer(command, 2, 5s));
  EXPECT_EQ(command.sample.modes()[0], wbi::msg::ControlMode::TORQUE);
  EXPECT_EQ(command.sample.modes()[1], wbi::msg::ControlMode::POSITION);
  EXPECT_DOUBLE_EQ(command.sample.references()[1], arm_position(2));

  robot->set_control_parameter(wbi::ControlParameter::kp, Eigen::Vector2d(100.0, 200.0));
  wbi::dds::Received<wbi::msg::ControlParameters> parameters;
  ASSERT_TRUE(peer.parameters().wait_newer(parameters, 0, 5s));
  EXPECT_DOUBLE_EQ(parameters.sample.kp()[1], 200.0);
  EXPECT_TRUE(std::isnan(parameters.sample.kd()[0]));  // untouched parameters travel as NaN

  wbi::dds::Participant estimator("estimator");
  wbi::dds::Subscriber<wbi::msg::EstimatorParameter> estimator_parameters(
      estimator, topics::estimator_parameters("arm_cmd"), qos::kCommand);
  ASSERT_TRUE(estimator_parameters.wait_for_publishers(1, 10s));
  // The proxy's writer may match this new reader a moment after the reader
  // matched it (docs: dds/README.md), and the parameter topic is volatile:
  // send until one arrives.
  wbi::dds::Received<wbi::msg::EstimatorParameter> parameter;
  bool received = false;
  for (int attempt = 0; attempt < 25 && !received; ++attempt) {
    robot->set_estimation_parameter("fixed_link", robot->frame_index("ee_link"));
    received = estimator_parameters.wait_newer(parameter, 0, 200ms);
  }
  ASSERT_TRUE(received);
  EXPECT_EQ(parameter.sample.name(), "fixed_link");
  EXPECT_EQ(parameter.sample.text(), "ee_link");
  EXPECT_THROW(robot->set_estimation_parameter("fixed_link", 1e6), wbi::Error);
}

// Lockstep (docs/conventions.md): only a reference answers a tick, that of the
// newest sample read; a mode switch answers none: it carries kNoTick before
// the first reference, the last reference's tick after.
TEST(DdsInterface, OnlyAReferenceAnswersALockstepTick) {
  ArmPeer peer("arm_tick");
  auto robot = wbi::make_dds_interface(arm_options("arm_tick"));
  robot->add_joints({"joint_1", "joint_2"});
  robot->init(10s);
  wbi::dds::Received<wbi::msg::ActuatorCommand> command;
  std::uint64_t seen = 0;
  const auto next = [&] {
    EXPECT_TRUE(peer.commands().wait_newer(command, seen, 5s));
    seen = command.count;
    return std::pair(command.sample.tick(), command.sample.source_stamp_ns());
  };
  const std::pair<std::uint64_t, std::int64_t> none(wbi::msg::kNoTick, 0);

  robot->set_control_mode(wbi::ControlMode::torque);
  EXPECT_EQ(next(), none) << "a mode switch before any reference";
  Eigen::VectorXd q(2);
  const auto first =
      robot->read_sensors(wbi::SensorKind::encoder_position, q, wbi::ReadMode::blocking);
  robot->set_control_mode(wbi::ControlMode::torque);
  EXPECT_EQ(next(), none) << "a mode switch after a read, before any reference";
  robot->set_control_reference(Eigen::Vector2d(1.0, 2.0));
  EXPECT_EQ(next(), std::pair(first.seq, first.source_ns));

  const auto second =
      robot->read_sensors(wbi::SensorKind::encoder_position, q, wbi::ReadMode::blocking);
  ASSERT_GT(second.seq, first.seq);
  robot->set_control_mode(wbi::ControlMode::torque, 1);
  EXPECT_EQ(next(), std::pair(first.seq, first.source_ns)) << "the last reference's tick";
  robot->set_control_reference(3.0, 1);
  EXPECT_EQ(next(), std::pair(second.seq, second.source_ns));
}

TEST(DdsInterface, ModelOverASubsetAgreesWithTheFullModel) {
  ArmPeer peer("arm_model");
  auto robot = wbi::make_dds_interface(arm_options("arm_model"));
  robot->add_joints({"joint_4", "joint_2"});
  robot->init(10s);

  // The full fixed-base model at the robot's measured posture.
  const auto full = wbi::model::load_urdf_file(wbi::test::project_model("arm7.urdf").string());
  wbi::model::Data data(full);
  Eigen::VectorXd q_full(full.nq);
  for (std::size_t j = 0; j < kArmJoints.size(); ++j) {
    q_full[full.joint_q_index[static_cast<std::size_t>(full.joint_id(kArmJoints[j]))]] =
        arm_position(j);
  }
  const Eigen::Vector3d gravity(0, 0, -9.81);
  const Eigen::VectorXd g_full = wbi::model::gravity_forces(full, data, q_full, gravity);
  const Eigen::MatrixXd M_full = wbi::model::mass_matrix(full, data, q_full);

  const Eigen::Vector2d q(arm_position(3), arm_position(1));
  const wbi::Transform world_H_base = wbi::Transform::Identity();
  Eigen::VectorXd g(8);
  robot->gravity_forces(q, world_H_base, gravity, g);
  Eigen::MatrixXd M(8, 8);
  robot->mass_matrix(q, world_H_base, M);
  const int v4 = full.joint_v_index[static_cast<std::size_t>(full.joint_id("joint_4"))];
  const int v2 = full.joint_v_index[static_cast<std::size_t>(full.joint_id("joint_2"))];
  EXPECT_NEAR(g[6], g_full[v4], 1e-9);
  EXPECT_NEAR(g[7], g_full[v2], 1e-9);
  EXPECT_NEAR(M(6, 7), M_full(v4, v2), 1e-9);
  EXPECT_NEAR(M(7, 7), M_full(v2, v2), 1e-9);
  EXPECT_TRUE(g.head<6>().isZero());  // fixed base: the base does not move

  const int ee = robot->frame_index("ee_link");
  wbi::Transform pose;
  robot->frame_pose(q, world_H_base, ee, pose);
  wbi::model::forward_kinematics(full, data, q_full);
  EXPECT_TRUE(pose.isApprox(wbi::model::frame_pose(full, data, full.frame_id("ee_link")), 1e-12));
  EXPECT_THROW(robot->frame_index("no_such_frame"), wbi::Error);
}

}  // namespace
