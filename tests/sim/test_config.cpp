// The plant configured by a robot config, and configuration errors that name what is wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "sim_test_common.hpp"
#include "wbi/model/com.hpp"
#include "wbi/model/crba.hpp"

namespace wbi::sim::test {
namespace {

// Expects `f` to throw std::exception whose message contains every `parts`.
template <typename F>
void expect_error(F&& f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    for (const char* p : parts) {
      EXPECT_NE(what.find(p), std::string::npos) << "'" << p << "' not in: " << what;
    }
  }
}

// A robot config file drives the plant: its contact geometry, sensors and options.
TEST(SimConfig, RobotConfigConfiguresThePlant) {
  const std::string yaml = R"(
urdf: )" + model_path("humanoid.urdf") +
                           R"(
gravity: [0, 0, -9.8]
initial_joint_positions: {l_knee: 0.3, r_knee: 0.3}
initial_base_position: [0, 0, 0.6]
place_on_ground: true
ground: {height: 0.1, friction: 0.6}
contacts:
  - {link: l_foot, box: {size: [0.2, 0.08, 0.03]}, position: [0.005, 0, -0.02]}
  - {link: r_foot, box: {size: [0.2, 0.08, 0.03]}, position: [0.005, 0, -0.02], friction: 0.9}
  - {link: l_hand, sphere: {radius: 0.02}}
  - {link: r_hand, capsule: {radius: 0.01, length: 0.1}, rpy: [1.5707963267948966, 0, 0]}
joints: {default: {friction: 0}, l_knee: {damping: 2}}
imus: [{name: imu, frame: imu_frame, gyro_noise: 0.01, accel_noise: 0.05}]
force_torque: [{name: l_ft, joint: l_foot_ft_sensor, force_noise: 0.5, torque_noise: 0.05}]
wbi:
  step: 0.002
  substeps: 4
  contact: {enable: true, tangential: regularized}
)";
  SimBackend sim(robot_config::parse_robot_config(yaml, "humanoid_test.yaml"));
  sim.configure();
  EXPECT_EQ(sim.description().n_joints(), 30);
  const auto& points = sim.ground_truth().contact_points;
  ASSERT_EQ(points.size(), 11u);  // 2 boxes × 4 corners + a sphere + a capsule's 2 ends
  EXPECT_EQ(points[0].friction, 0.6);
  EXPECT_EQ(points[4].friction, 0.9);
  EXPECT_EQ(points[8].radius, 0.02);
  EXPECT_NEAR(std::abs(points[9].p_F.y() - points[10].p_F.y()), 0.1, 1e-12);  // capsule along y
  EXPECT_EQ(sim.ground_truth().contact_links.size(), 4u);
  // placed on the ground: the lowest point (a sole corner; the hands hang higher) at 0.1
  double z_min = 1.0;
  for (const auto& cp : points) {
    z_min = std::min(z_min, cp.p_W.z());
  }
  EXPECT_NEAR(z_min, 0.1, 1e-12);
  EXPECT_EQ(sim.description().ft_names[0], "l_ft");
  EXPECT_EQ(sim.stamp(), Time(0));
  sim.activate();
  sim.step();
  EXPECT_EQ(sim.stamp(), Time(2000000));  // wbi.step
}

// The project's humanoid.yaml lists its URDF's <collision> boxes: the same contact
// points, in the same order, as a configuration without contacts (the URDF's).
TEST(SimConfig, HumanoidFileMatchesTheUrdfBoxes) {
  SimBackend from_file(robot_config::load_robot_config(
      (wbi::test::source_dir() / "deploy" / "robots" / "humanoid.yaml").string()));
  SimBackend from_urdf(humanoid_config());
  from_file.configure();
  from_urdf.configure();
  const auto& a = from_file.ground_truth().contact_points;
  const auto& b = from_urdf.ground_truth().contact_points;
  ASSERT_EQ(a.size(), 8u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].p_F, b[i].p_F);
    EXPECT_EQ(a[i].link, b[i].link);
    EXPECT_EQ(a[i].friction, b[i].friction);
  }
  EXPECT_EQ(from_file.ground_truth().contact_links, from_urdf.ground_truth().contact_links);
}

// The real robots' files configure the own plant: their sole boxes become contact
// points, placed on the ground, and their sensors exist.
TEST(SimConfig, RealRobotFilesConfigureThePlant) {
  struct Robot {
    const char* file;
    const char* urdf;
    std::size_t points, fts;
  };
  for (const Robot& robot : {Robot{"icub3.yaml", "iCubGenova09/model.urdf", 16, 8},
                             Robot{"talos.yaml", "talos/talos_reduced.urdf", 8, 4}}) {
    const auto shared = wbi::test::shared_models_dir();
    if (!shared || !std::filesystem::exists(*shared / robot.urdf)) {
      GTEST_SKIP() << wbi::test::kSharedMissing << " (expected ../shared/models/" << robot.urdf
                   << ")";
    }
    SimBackend sim(robot_config::load_robot_config(
        (wbi::test::source_dir() / "deploy" / "robots" / robot.file).string()));
    sim.configure();
    const auto& points = sim.ground_truth().contact_points;
    ASSERT_EQ(points.size(), robot.points) << robot.file;
    double z_min = 1.0;
    for (const auto& cp : points) {
      z_min = std::min(z_min, cp.p_W.z());
    }
    EXPECT_NEAR(z_min, 0.0, 1e-12) << robot.file;
    EXPECT_EQ(sim.description().ft_names.size(), robot.fts) << robot.file;
    EXPECT_EQ(sim.description().n_joints(), 32) << robot.file;
  }
}

TEST(SimConfig, UnknownNamesAreErrors) {
  auto configure = [](RobotConfig c) {
    SimBackend sim(std::move(c));
    sim.configure();
  };
  RobotConfig c = humanoid_config();
  c.initial_joint_positions["l_kne"] = 0.1;
  expect_error([&] { configure(c); }, {"initial_joint_positions", "l_kne"});
  c = humanoid_config();
  c.imus[0].frame = "imu_fram";
  expect_error([&] { configure(c); }, {"imu_fram"});
  c = humanoid_config();
  c.force_torque[0].joint = "l_knee";
  expect_error([&] { configure(c); }, {"l_knee", "not a fixed joint"});
  c = humanoid_config();
  c.force_torque[0].joint = "l_foot_ft";
  expect_error([&] { configure(c); }, {"unknown joint", "l_foot_ft"});
  c = humanoid_config();
  c.pushes.push_back({"torso", 0.0, 0.1, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()});
  expect_error([&] { configure(c); }, {"pushes", "torso"});
  c = humanoid_config();
  c.contacts.emplace_back();
  c.contacts.back().link = "left_foot";
  c.contacts.back().size = Eigen::Vector3d::Ones();
  expect_error([&] { configure(c); }, {"contact", "left_foot"});
  c = humanoid_config();
  c.joints["l_kne"].armature = 0.1;
  expect_error([&] { configure(c); }, {"joints", "unknown joint", "l_kne"});
  c = humanoid_config();
  c.joints["l_foot_ft_sensor"].armature = 0.1;
  expect_error([&] { configure(c); }, {"joints", "l_foot_ft_sensor", "fixed"});
  c = humanoid_config();
  c.urdf = "/nonexistent/robot.urdf";
  expect_error([&] { configure(c); }, {"/nonexistent/robot.urdf"});
  c.urdf.clear();
  expect_error([&] { configure(c); }, {"urdf", "required"});
  // commands before activate() are not applied; read/write before configure() throw
  SimBackend sim(humanoid_config());
  expect_error([&] { sim.read(Time(0), Duration(1000000)); }, {"read()", "UNCONFIGURED"});
  expect_error([&] { sim.activate(); }, {"activate()", "INACTIVE"});
}

TEST(SimConfig, LifecycleTransitions) {
  SimBackend sim(humanoid_config());
  using wbi::LifecycleState;
  EXPECT_EQ(sim.state(), LifecycleState::unconfigured);
  sim.configure();
  EXPECT_EQ(sim.state(), LifecycleState::inactive);
  // INACTIVE: readable, commands not applied (a torque command is replaced by IDLE)
  sim.read(sim.stamp(), Duration(1000000));
  sim.commands().mode.assign(30, actuation::OutputMode::kTorque);
  sim.commands().value.setConstant(5.0);
  sim.write(sim.stamp(), Duration(1000000));
  sim.step();
  EXPECT_EQ(sim.ground_truth().tau_actuator.cwiseAbs().maxCoeff(), 0.0);
  sim.activate();
  sim.commands().mode.assign(30, actuation::OutputMode::kTorque);
  sim.commands().value.setConstant(1.0);
  sim.write(sim.stamp(), Duration(1000000));
  sim.step();
  EXPECT_EQ(sim.ground_truth().tau_actuator.minCoeff(), 1.0);
  sim.commands().value.resize(3);  // wrong size: rejected
  expect_error([&] { sim.write(sim.stamp(), Duration(1000000)); }, {"wrong size", "30"});
  sim.deactivate();
  expect_error(
      [&] {
        sim.cleanup();
        sim.step();
      },
      {"configure() first"});
  EXPECT_EQ(sim.state(), LifecycleState::unconfigured);
  sim.configure();  // again, from the initial state
  EXPECT_EQ(sim.time(), 0.0);
  sim.activate();
  sim.shutdown();
  EXPECT_EQ(sim.state(), LifecycleState::finalized);
  expect_error([&] { sim.read(sim.stamp(), Duration(1000000)); }, {"FINALIZED"});
}

// A push on the floating robot in zero gravity, no contact: the momentum changes by the
// impulse, m Δċ = F T, whatever the joints do (internal forces).
TEST(SimPlant, PushChangesMomentumByTheImpulse) {
  RobotConfig c = humanoid_config();
  c.gravity.setZero();
  c.wbi.contact.enable = robot_config::ContactModel::Enable::kOff;
  c.place_on_ground = false;
  c.pushes.push_back(
      {"root_link", 0.1, 0.2, Eigen::Vector3d(10.0, -5.0, 2.0), Eigen::Vector3d(0.0, 0.05, 0.1)});
  SimBackend sim(c);
  sim.configure();
  const model::Model& m = sim.model();
  model::Data data(m);
  for (int k = 0; k < 500; ++k) {
    sim.write(sim.stamp(), Duration(1000000));
    sim.step();
  }
  const auto& gt = sim.ground_truth();
  const Eigen::Vector3d dc = model::com_jacobian(m, data, gt.q) * gt.nu;
  const Eigen::Vector3d expected = Eigen::Vector3d(10.0, -5.0, 2.0) * 0.2 / m.total_mass;
  std::cout << "[measured] push 0.2 s: CoM velocity " << dc.transpose() << ", expected "
            << expected.transpose() << "\n";
  EXPECT_LT((dc - expected).norm(), 2e-4 * expected.norm());
}

// Free fall (no contact, joints IDLE): every body falls with g, the accelerometer
// reads 0; orientation and gyro are those of the pelvis (the IMU is fixed to it,
// same axes). (Standing, it reads +g: SimPlant.HumanoidStandsStill.)
TEST(SimPlant, ImuReadsFreeFallOrientationAndRate) {
  RobotConfig c = humanoid_config();
  c.wbi.contact.enable = robot_config::ContactModel::Enable::kOff;
  c.place_on_ground = false;
  robot_config::complete_from_urdf(c);
  for (auto& [name, joint] : c.joints) {
    joint.friction = 0.0;
  }
  const Eigen::Quaterniond quat(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()));
  c.initial_base_orientation << quat.w(), quat.x(), quat.y(), quat.z();
  SimBackend sim(c);
  sim.configure();
  for (int k = 0; k < 20; ++k) {
    sim.write(sim.stamp(), Duration(1000000));
    sim.step();
  }
  sim.read(sim.stamp(), Duration(1000000));
  const auto& imu = sim.readings().imus[0];
  std::cout << "[measured] IMU in free fall: accel " << imu.accel.transpose() << "\n";
  EXPECT_LT(imu.accel.norm(), 1e-9);
  for (const auto& ft : sim.readings().force_torque) {
    EXPECT_LT(ft.wrench.norm(), 1e-9);  // nothing pulls on a free-falling foot
  }
  EXPECT_LT((imu.orientation - sim.ground_truth().base_orientation).norm(), 1e-12);
  // spinning at rest in zero gravity: gyro = R_WBᵀ ω
  Eigen::VectorXd q = sim.ground_truth().q;
  Eigen::VectorXd nu = Eigen::VectorXd::Zero(sim.model().nv);
  nu.segment<3>(3) = Eigen::Vector3d(0.1, -0.2, 0.3);
  sim.set_state(q, nu);
  sim.read(sim.stamp(), Duration(1000000));
  const Eigen::Matrix3d R = quat.toRotationMatrix();
  EXPECT_LT((sim.readings().imus[0].gyro - R.transpose() * nu.segment<3>(3)).norm(), 1e-12);
}

}  // namespace
}  // namespace wbi::sim::test
