// SimConfig from YAML, and configuration errors that name what is wrong.
#include <gtest/gtest.h>

#include <map>
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

TEST(SimConfig, ParsesEveryKey) {
  const std::string yaml = R"(
urdf: )" + model_path("humanoid.urdf") +
                           R"(
step: 0.002
substeps: 4
gravity: [0, 0, -9.8]
initial_joint_positions: {l_knee: 0.3, r_knee: 0.3}
initial_base_position: [0, 0, 0.6]
initial_base_orientation: [1, 0, 0, 0]
place_on_ground: true
joint_damping: false
joint_friction: true
friction_velocity: 0.02
joint_limits: {stiffness: 1000, damping: 10}
contact:
  enable: true
  stiffness: 40000
  damping: 80
  friction: 0.6
  tangential: regularized
  tangential_stiffness: 20000
  tangential_damping: 50
  slip_velocity: 0.002
  links: [l_foot, r_foot]
  points: [{link: l_hand, position: [0, 0, -0.02]}]
encoders: {counts_per_revolution: 4096, position_noise: 0.001, velocity_noise: 0.01, torque_noise: 0.1}
motor: {voltage: 48, resistance: 0.5, torque_constant: 0.1, back_emf: 0.1}
imus: [{name: imu, frame: imu_frame, gyro_noise: 0.01, accel_noise: 0.05}]
force_torque: [{name: l_ft, joint: l_foot_ft_sensor, force_noise: 0.5, torque_noise: 0.05}]
pushes: [{link: root_link, start: 1.0, duration: 0.2, force: [50, 0, 0], point: [0, 0, 0.1]}]
seed: 7
)";
  const SimConfig c = parse_sim_config(yaml);
  EXPECT_EQ(c.step, 0.002);
  EXPECT_EQ(c.substeps, 4);
  EXPECT_EQ(c.initial_joint_positions.at("l_knee"), 0.3);
  EXPECT_TRUE(c.place_on_ground);
  EXPECT_FALSE(c.joint_damping);
  EXPECT_EQ(c.contact.enable, ContactConfig::Enable::kOn);
  EXPECT_EQ(c.contact.tangential, ContactConfig::Tangential::kRegularized);
  EXPECT_EQ(c.contact.links.size(), 2u);
  ASSERT_EQ(c.contact.points.size(), 1u);
  EXPECT_EQ(c.contact.points[0].position.z(), -0.02);
  EXPECT_EQ(c.encoders.counts_per_revolution, 4096.0);
  EXPECT_EQ(c.motor.voltage, 48.0);
  ASSERT_EQ(c.imus.size(), 1u);
  ASSERT_EQ(c.force_torque.size(), 1u);
  ASSERT_EQ(c.pushes.size(), 1u);
  EXPECT_EQ(c.pushes[0].force.x(), 50.0);
  EXPECT_EQ(c.seed, 7u);
  SimBackend sim(c);
  sim.configure();
  EXPECT_EQ(sim.description().n_joints(), 30);
  EXPECT_EQ(sim.ground_truth().contact_points.size(), 9u);  // 2 boxes × 4 corners + 1
  EXPECT_EQ(sim.description().ft_names[0], "l_ft");
}

TEST(SimConfig, YamlErrorsNameTheKey) {
  expect_error([] { parse_sim_config("urdf: x\nstepp: 0.001\n"); }, {"stepp", "unknown key"});
  expect_error([] { parse_sim_config("contact: {stifness: 3}\n"); },
               {"contact.stifness", "unknown key"});
  expect_error([] { parse_sim_config("step: fast\n"); }, {"step", "wrong type"});
  expect_error([] { parse_sim_config("step: -1\n"); }, {"step", "> 0"});
  expect_error([] { parse_sim_config("gravity: [0, 0]\n"); }, {"gravity", "3 numbers"});
  expect_error([] { parse_sim_config("contact: {tangential: sticky}\n"); },
               {"contact.tangential", "sticky"});
  expect_error([] { parse_sim_config("imus: [{name: a}]\n"); }, {"imus[0]", "frame"});
  expect_error([] { parse_sim_config("pushes: [{link: a, forse: [1, 2, 3]}]\n"); },
               {"pushes[0].forse"});
  expect_error([] { parse_sim_config("a: [1,\n"); }, {"YAML error", "line"});
  expect_error([] { parse_sim_config("armature: [0.1]\n"); }, {"armature", "map joint"});
  expect_error([] { parse_sim_config("armature: {j1: heavy}\n"); },
               {"armature.j1", "expected a number"});
  expect_error([] { parse_sim_config("armature: {j1: -0.1}\n"); }, {"armature.j1", ">= 0"});
  expect_error([] { parse_sim_config("armature: {j1: .nan}\n"); }, {"armature.j1", "finite"});
  EXPECT_EQ(parse_sim_config("armature: {j1: 0.5, j2: 0}\n").armature,
            (std::map<std::string, double>{{"j1", 0.5}, {"j2", 0.0}}));
  expect_error([] { load_sim_config_file("/nonexistent/sim.yaml"); }, {"/nonexistent/sim.yaml"});
}

TEST(SimConfig, UnknownNamesAreErrors) {
  auto configure = [](SimConfig c) {
    SimBackend sim(std::move(c));
    sim.configure();
  };
  SimConfig c = humanoid_config();
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
  c.contact.links = {"l_foot", "left_foot"};
  expect_error([&] { configure(c); }, {"contact.links", "left_foot"});
  c = humanoid_config();
  c.armature["l_kne"] = 0.1;
  expect_error([&] { configure(c); }, {"armature", "unknown joint", "l_kne"});
  c = humanoid_config();
  c.armature["l_foot_ft_sensor"] = 0.1;
  expect_error([&] { configure(c); }, {"armature", "l_foot_ft_sensor", "fixed"});
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
  using actuation::LifecycleState;
  EXPECT_EQ(sim.state(), LifecycleState::kUnconfigured);
  sim.configure();
  EXPECT_EQ(sim.state(), LifecycleState::kInactive);
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
  EXPECT_EQ(sim.state(), LifecycleState::kUnconfigured);
  sim.configure();  // again, from the initial state
  EXPECT_EQ(sim.time(), 0.0);
  sim.activate();
  sim.shutdown();
  EXPECT_EQ(sim.state(), LifecycleState::kFinalized);
  expect_error([&] { sim.read(sim.stamp(), Duration(1000000)); }, {"FINALIZED"});
}

// A push on the floating robot in zero gravity, no contact: the momentum changes by the
// impulse, m Δċ = F T, whatever the joints do (internal forces).
TEST(SimPlant, PushChangesMomentumByTheImpulse) {
  SimConfig c = humanoid_config();
  c.gravity.setZero();
  c.contact.enable = ContactConfig::Enable::kOff;
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
  SimConfig c = humanoid_config();
  c.contact.enable = ContactConfig::Enable::kOff;
  c.place_on_ground = false;
  c.joint_friction = false;
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
