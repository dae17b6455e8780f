// Joint torques and external wrenches of a simulated robot over DDS, the
// project's arm (deploy/robots/arm.yaml) run by sim_robot and the estimator in
// this process (sim_rig::InProcessRobot), read by the whole-body interface:
//  - joint_torque_sensors: none — the sensor samples carry no joint torque and
//    the interface's read of joint torques is an error naming the joints;
//  - a subset — one entry per joint, NaN (no reading) for the others, only the
//    joints with a sensor readable, the state's tau finite;
//  - the ground truth's applied torque is the commanded torque in torque mode
//    (within the limits of the joint controller and the motor model), and a
//    configured push is its own entry, with its force during its window and
//    zero outside it — on the own plant and on MuJoCo.
#include <gtest/gtest.h>

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <wbi/msg/sensors.h>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>
#include <wbi/sim_robot/engine_registry.hpp>

#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;

const wbi::IdList kJoints{"joint_1", "joint_2", "joint_3", "joint_4",
                          "joint_5", "joint_6", "joint_7"};

// deploy/robots/arm.yaml with `extra` keys, written to a file of its own (its
// URDF made absolute): the robot config of one test.
std::string arm_config(const std::string& name, const std::string& extra) {
  const auto robots = wbi::test::source_dir() / "deploy" / "robots";
  std::ifstream in(robots / "arm.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string relative = "urdf: ../../models/arm7.urdf";
  const auto at = yaml.find(relative);
  EXPECT_NE(at, std::string::npos) << "arm.yaml names its URDF otherwise";
  yaml.replace(at, relative.size(), "urdf: " + wbi::test::project_model("arm7.urdf").string());
  const auto dir = std::filesystem::temp_directory_path() /
                   ("wbi_sim_robot_torques_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / (name + ".yaml");
  std::ofstream(file) << yaml << "\n" << extra << "\n";
  return file.string();
}

// The arm in sim_robot (`engine`) and its estimator; `sim` adds sim_robot parameters.
std::unique_ptr<wbi::sim_rig::InProcessRobot> arm_rig(const std::string& robot,
                                                      const std::string& engine,
                                                      const std::string& config,
                                                      const std::string& sim) {
  return std::make_unique<wbi::sim_rig::InProcessRobot>(
      robot, "robot: " + robot + "\nengine: " + engine + "\nconfig: " + config + "\n" + sim,
      "robot: " + robot + "\nmethod: backward-difference\ncutoff: 100\n");
}

std::unique_ptr<wbi::WholeBodyInterface> arm_interface(const std::string& robot,
                                                       const std::string& controller) {
  wbi::DdsInterfaceOptions options;
  options.robot = robot;
  options.controller = controller;
  options.urdf = wbi::test::project_model("arm7.urdf").string();
  options.max_age_s = 5.0;  // a loaded machine; this test is not about staleness
  auto arm = wbi::make_dds_interface(options);
  arm->add_joints(kJoints);
  return arm;
}

// The message of the error `read` throws (a wbi::Error), or a failure.
template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const wbi::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// The next sensor sample after `sample` (bounded wait).
void next_sample(const wbi::dds::Subscriber<wbi::msg::SensorSample>& sensors,
                 wbi::dds::Received<wbi::msg::SensorSample>& sample) {
  ASSERT_TRUE(sensors.wait_newer(sample, sample.count, 10s)) << "no sensor sample";
}

TEST(SimRobotTorques, WithoutJointTorqueSensorsNoTorqueIsPublishedNorRead) {
  const std::string robot = "torques_none";
  auto rig = arm_rig(robot, "wbi", arm_config(robot, "joint_torque_sensors: none"), "");
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(rig->participant(), topics::sensors(robot),
                                                       qos::kStream);
  auto arm = arm_interface(robot, "reader");
  rig->start_simulation();
  arm->init(20s);
  wbi::dds::Received<wbi::msg::SensorSample> sample;
  next_sample(sensors, sample);
  EXPECT_TRUE(sample.sample.joint_torque().empty()) << "an empty array: no such sensor";
  EXPECT_EQ(sample.sample.encoder_position().size(), 7u);

  Eigen::VectorXd tau(7);
  EXPECT_EQ(error_of([&] { arm->read_sensors(wbi::SensorKind::joint_torque, tau); }),
            "robot 'torques_none' has no joint-torque sensor on joints joint_1, joint_2, joint_3, "
            "joint_4, joint_5, joint_6, joint_7 (it has no joint-torque sensors)");
  Eigen::VectorXd one(1);
  EXPECT_EQ(error_of([&] { arm->read_sensor(wbi::SensorKind::joint_torque, 3, one); }),
            "robot 'torques_none' has no joint-torque sensor on joint joint_4 (it has no "
            "joint-torque sensors)");
  // The state's torque estimate: answered, finite (no sensor: 0 for now).
  arm->read_estimates(wbi::EstimateKind::joint_torque, tau);
  EXPECT_TRUE(tau.allFinite()) << tau.transpose();
}

TEST(SimRobotTorques, WithSomeJointTorqueSensorsOnlyTheirJointsAreRead) {
  const std::string robot = "torques_some";
  auto rig =
      arm_rig(robot, "wbi", arm_config(robot, "joint_torque_sensors: [joint_6, joint_2]"), "");
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(rig->participant(), topics::sensors(robot),
                                                       qos::kStream);
  auto arm = arm_interface(robot, "reader");
  rig->start_simulation();
  arm->init(20s);
  wbi::dds::Received<wbi::msg::SensorSample> sample;
  next_sample(sensors, sample);
  const auto& torque = sample.sample.joint_torque();
  ASSERT_EQ(torque.size(), 7u) << "one entry per joint";
  for (std::size_t j = 0; j < torque.size(); ++j) {
    const bool sensed = j == 1 || j == 5;
    EXPECT_EQ(std::isfinite(torque[j]), sensed) << kJoints[j] << ": " << torque[j];
  }

  Eigen::VectorXd tau(7);
  EXPECT_EQ(error_of([&] { arm->read_sensors(wbi::SensorKind::joint_torque, tau); }),
            "robot 'torques_some' has no joint-torque sensor on joints joint_1, joint_3, joint_4, "
            "joint_5, joint_7 (the joints with one: joint_2, joint_6)");
  Eigen::VectorXd one(1);
  EXPECT_EQ(error_of([&] { arm->read_sensor(wbi::SensorKind::joint_torque, 0, one); }),
            "robot 'torques_some' has no joint-torque sensor on joint joint_1 (the joints with "
            "one: joint_2, joint_6)");
  for (const int j : {1, 5}) {
    arm->read_sensor(wbi::SensorKind::joint_torque, j, one);
    EXPECT_TRUE(std::isfinite(one[0])) << kJoints[static_cast<std::size_t>(j)];
  }
  // The state's tau never carries the NaN of the joints without a sensor.
  ASSERT_TRUE(sensors.wait_newer(sample, sample.count + 20, 10s)) << "the robot stopped";
  arm->read_estimates(wbi::EstimateKind::joint_torque, tau);
  EXPECT_TRUE(tau.allFinite()) << tau.transpose();
}

// ---- ground truth: applied torque and pushes, on each engine ----

class SimRobotGroundTruth : public ::testing::TestWithParam<std::string> {};

TEST_P(SimRobotGroundTruth, AppliedTorqueIsTheCommandAndAPushIsItsOwnEntry) {
  const std::string engine = GetParam();
  if (!wbi::sim_robot::builtin_engines().contains(engine)) {
    GTEST_SKIP() << "engine '" << engine << "' is not built (libmujoco-dev)";
  }
  const std::string robot = "truth_" + engine;
  // A push on link_4 over [10 ms, 20 ms) at a point 0.1 m along its x axis.
  const Eigen::Vector3d force(0.0, 0.0, 30.0);
  const std::int64_t start_ns = 10'000'000;
  const std::int64_t end_ns = 20'000'000;
  auto rig = arm_rig(robot, engine,
                     arm_config(robot,
                                "pushes:\n  - {link: link_4, start: 0.01, duration: 0.01, "
                                "force: [0, 0, 30], point: [0.1, 0, 0]}"),
                     "lockstep: true\nlockstep_controllers: [torque]\n");
  wbi::dds::Subscriber<wbi::msg::GroundTruth> truth(rig->participant(), topics::ground_truth(robot),
                                                    qos::kStream);
  auto arm = arm_interface(robot, "torque");
  rig->start_simulation();
  arm->init(20s);
  // Torques within the effort limits, small enough that no joint reaches its
  // velocity limit in 30 ms (beyond it the joint controller brakes: checked below).
  Eigen::VectorXd command(7);
  command << 4.0, -3.0, 2.0, -1.5, 1.0, -0.5, 0.05;
  const Eigen::VectorXd velocity_limit =
      (Eigen::VectorXd(7) << 1.7, 1.7, 2.0, 2.0, 2.6, 3.1, 3.1).finished();  // models/arm7.urdf
  arm->set_control_mode(wbi::ControlMode::torque);
  wbi::dds::Received<wbi::msg::GroundTruth> state;
  Eigen::VectorXd q(7);
  int pushed = 0;
  for (std::uint64_t k = 0; k < 30; ++k) {
    const wbi::Stamp stamp = arm->read_sensors(wbi::SensorKind::encoder_position, q,
                                               wbi::ReadMode::blocking);  // tick k
    ASSERT_EQ(stamp.seq, k);
    arm->set_control_reference(command);  // answers tick k: applied over the step to k + 1
    while (state.count == 0 || state.sample.header().seq() < k + 1) {
      ASSERT_TRUE(truth.wait_newer(state, state.count, 10s)) << "no ground truth after tick " << k;
    }
    const auto& t = state.sample;
    ASSERT_EQ(t.header().seq(), k + 1);
    ASSERT_EQ(t.applied_torque().size(), 7u);
    for (int j = 0; j < 7; ++j) {
      const auto u = static_cast<std::size_t>(j);
      ASSERT_LT(std::abs(t.dq()[u]), velocity_limit[j]) << kJoints[u] << ": the test's premise";
      EXPECT_EQ(t.applied_torque()[u], command[j])
          << engine << ": tick " << k + 1 << ", " << kJoints[u];
    }
    // The push acts in the last integration step before the stamp: start < stamp <= end.
    ASSERT_EQ(t.push_wrenches().size(), 1u);
    const auto& push = t.push_wrenches()[0];
    EXPECT_EQ(push.link().to_string(), "link_4");
    const auto& f = push.wrench().force();
    const auto& m = push.wrench().torque();
    const Eigen::Vector3d f_W(f.x(), f.y(), f.z());
    const Eigen::Vector3d m_W(m.x(), m.y(), m.z());
    const bool active = t.header().stamp_ns() > start_ns && t.header().stamp_ns() <= end_ns;
    pushed += active ? 1 : 0;
    if (active) {
      EXPECT_EQ(f_W, force) << engine << ": tick " << k + 1;
      // About link_4's origin: (R_WL [0.1, 0, 0]) × f, perpendicular to f, |m| <= 0.1 |f|.
      EXPECT_NEAR(m_W.dot(force), 0.0, 1e-9) << m_W.transpose();
      EXPECT_LE(m_W.norm(), 0.1 * force.norm() + 1e-9) << m_W.transpose();
      EXPECT_GT(m_W.norm(), 0.0) << "the point is off the link origin";
    } else {
      EXPECT_EQ(f_W, Eigen::Vector3d::Zero()) << engine << ": tick " << k + 1;
      EXPECT_EQ(m_W, Eigen::Vector3d::Zero()) << engine << ": tick " << k + 1;
    }
    EXPECT_TRUE(t.contact_wrenches().empty()) << "a push is no contact";
  }
  EXPECT_EQ(pushed, 10) << "10 ticks of 1 ms in the window";
}

INSTANTIATE_TEST_SUITE_P(Engines, SimRobotGroundTruth, ::testing::Values("wbi", "mujoco"),
                         [](const auto& engine) { return engine.param; });

}  // namespace
