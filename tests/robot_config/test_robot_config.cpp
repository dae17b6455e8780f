// The robot config schema: values, resolution against the URDF, and one test per
// error class (every error is one line "file:line: key: what").
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::robot_config {
namespace {

std::string humanoid_urdf() { return wbi::test::project_model("humanoid.urdf").string(); }

// A valid document on the humanoid, then `rest` (line 2 onwards).
std::string humanoid(const std::string& rest) { return "urdf: " + humanoid_urdf() + "\n" + rest; }

// The one-line message of parsing `yaml` as "robot.yaml".
std::string error_of(const std::string& yaml) {
  try {
    parse_robot_config(yaml, "robot.yaml");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
    return what;
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return "";
}

// Expects the error to start with "robot.yaml:<line>: <key>: " and to contain `what`.
void expect_error(const std::string& yaml, int line, const std::string& key,
                  const std::string& what) {
  const std::string message = error_of(yaml);
  const std::string head = "robot.yaml:" + std::to_string(line) + ": " + key + ": ";
  EXPECT_EQ(message.rfind(head, 0), 0u) << "expected '" << head << "…', got: " << message;
  EXPECT_NE(message.find(what), std::string::npos) << "'" << what << "' not in: " << message;
}

TEST(RobotConfig, ParsesEveryKey) {
  const RobotConfig c = parse_robot_config(humanoid(R"(fixed_base: false
gravity: [0, 0, -9.8]
initial_joint_positions: {l_knee: 0.3, r_knee: 0.3}
initial_base_position: [0, 0, 0.6]
initial_base_orientation: [1, 0, 0, 0]
place_on_ground: true
ground: {height: 0.01, friction: 0.7}
contacts:
  - {link: l_foot, box: {size: [0.2, 0.08, 0.03]}, position: [0.005, 0, -0.02], rpy: [0, 0, 1.5707963267948966]}
  - {link: l_hand, sphere: {radius: 0.03}, friction: 0.5}
  - {link: r_hand, capsule: {radius: 0.01, length: 0.1}}
joints:
  default: {armature: 0.01}
  l_knee: {armature: 0.2, damping: 3, friction: 0.4, kp: 80, kd: 2}
imus: [{name: imu, frame: imu_frame, gyro_noise: 0.01, accel_noise: 0.05}]
force_torque: [{name: l_ft, joint: l_foot_ft_sensor, force_noise: 0.5, torque_noise: 0.05}]
pushes: [{link: root_link, start: 1.0, duration: 0.2, force: [50, 0, 0], point: [0, 0, 0.1]}]
wbi:
  step: 0.002
  substeps: 4
  friction_velocity: 0.02
  joint_limits: {stiffness: 1000, damping: 10}
  contact: {enable: true, stiffness: 40000, damping: 80, tangential: regularized,
            tangential_stiffness: 20000, tangential_damping: 50, slip_velocity: 0.002}
  encoders: {counts_per_revolution: 4096, position_noise: 0.001, velocity_noise: 0.01, torque_noise: 0.1}
  motor: {voltage: 48, resistance: 0.5, torque_constant: 0.1, back_emf: 0.1}
  seed: 7
mujoco: {timestep: 0.001, substeps: 1, integrator: RK4, solref: [0.01, 0.9],
         solimp: [0.8, 0.9, 0.002, 0.4, 3], cone: elliptic, impratio: 10,
         joint_friction: constraint}
)"),
                                           "robot.yaml");
  EXPECT_EQ(c.urdf, humanoid_urdf());
  EXPECT_EQ(c.gravity.z(), -9.8);
  EXPECT_EQ(c.initial_joint_positions.at("l_knee"), 0.3);
  EXPECT_EQ(c.initial_base_position.z(), 0.6);
  EXPECT_TRUE(c.place_on_ground);
  EXPECT_EQ(c.ground.height, 0.01);
  ASSERT_EQ(c.contacts.size(), 3u);
  EXPECT_EQ(c.contacts[0].shape, wbi::ContactShape::box);
  EXPECT_EQ(c.contacts[0].size.x(), 0.2);
  EXPECT_NEAR((c.contacts[0].rotation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(),
              0.0, 1e-15);                 // yaw 90°
  EXPECT_EQ(c.contacts[0].friction, 0.7);  // the ground's
  EXPECT_EQ(c.contacts[1].shape, wbi::ContactShape::sphere);
  EXPECT_EQ(c.contacts[1].radius, 0.03);
  EXPECT_EQ(c.contacts[1].friction, 0.5);
  EXPECT_EQ(c.contacts[2].shape, wbi::ContactShape::capsule);
  EXPECT_EQ(c.contacts[2].length, 0.1);
  EXPECT_EQ(c.joints.size(), 30u);  // every model joint
  EXPECT_EQ(c.joints.at("l_knee").armature, 0.2);
  EXPECT_EQ(c.joints.at("l_knee").damping, 3.0);
  EXPECT_EQ(c.joints.at("l_knee").friction, 0.4);
  EXPECT_EQ(c.joints.at("r_knee").armature, 0.01);  // default
  EXPECT_EQ(c.joints.at("r_knee").damping, 0.5);    // URDF <dynamics>
  EXPECT_EQ(c.joints.at("r_knee").friction, 0.3);
  EXPECT_EQ(c.joints.at("l_knee").kp, 80.0);
  EXPECT_EQ(c.joints.at("l_knee").kd, 2.0);
  EXPECT_EQ(c.joints.at("r_knee").kp, 0.0);  // not given: the joint controller's default
  EXPECT_EQ(armature_by_joint(c).at("l_knee"), 0.2);
  EXPECT_EQ(armature_by_joint(c).size(), 30u);
  ASSERT_EQ(c.imus.size(), 1u);
  EXPECT_EQ(c.imus[0].accel_noise, 0.05);
  ASSERT_EQ(c.force_torque.size(), 1u);
  EXPECT_EQ(c.force_torque[0].joint, "l_foot_ft_sensor");
  ASSERT_EQ(c.pushes.size(), 1u);
  EXPECT_EQ(c.pushes[0].force.x(), 50.0);
  EXPECT_EQ(c.wbi.step, 0.002);
  EXPECT_EQ(c.wbi.substeps, 4);
  EXPECT_EQ(c.wbi.friction_velocity, 0.02);
  EXPECT_EQ(c.wbi.joint_limits.damping, 10.0);
  EXPECT_EQ(c.wbi.contact.enable, ContactModel::Enable::kOn);
  EXPECT_EQ(c.wbi.contact.tangential, ContactModel::Tangential::kRegularized);
  EXPECT_EQ(c.wbi.contact.slip_velocity, 0.002);
  EXPECT_EQ(c.wbi.encoders.counts_per_revolution, 4096.0);
  EXPECT_EQ(c.wbi.motor.voltage, 48.0);
  EXPECT_EQ(c.wbi.seed, 7u);
  EXPECT_EQ(c.mujoco.timestep, 0.001);
  EXPECT_EQ(c.mujoco.substeps, 1);
  EXPECT_EQ(c.mujoco.integrator, wbi::Integrator::rk4);
  EXPECT_EQ(c.mujoco.solref[1], 0.9);
  EXPECT_EQ(c.mujoco.solimp[4], 3.0);
  EXPECT_EQ(c.mujoco.cone, MujocoOptions::Cone::kElliptic);
  EXPECT_EQ(c.mujoco.impratio, 10.0);
  EXPECT_EQ(c.mujoco.joint_friction, MujocoOptions::JointFriction::kConstraint);
}

// Without "joints:" and "contacts:", the URDF's <dynamics> and <collision> boxes;
// a relative URDF path is relative to the file.
TEST(RobotConfig, DefaultsComeFromTheUrdf) {
  const auto file = wbi::test::source_dir() / "deploy" / "robots" / "any.yaml";
  const RobotConfig c = parse_robot_config("urdf: ../../models/humanoid.urdf\n", file.string());
  EXPECT_EQ(c.urdf, humanoid_urdf());
  ASSERT_EQ(c.contacts.size(), 2u);  // the feet's boxes, links in name order
  EXPECT_EQ(c.contacts[0].link, "l_foot");
  EXPECT_EQ(c.contacts[1].link, "r_foot");
  EXPECT_EQ(c.contacts[0].size, Eigen::Vector3d(0.2, 0.08, 0.03));
  EXPECT_EQ(c.contacts[0].friction, 0.8);
  EXPECT_EQ(c.joints.size(), 30u);
  for (const auto& [name, joint] : c.joints) {
    EXPECT_EQ(joint.armature, 0.0) << name;
  }
  EXPECT_EQ(c.wbi.step, 1e-3);
  EXPECT_EQ(c.wbi.substeps, 2);
  EXPECT_EQ(c.mujoco.integrator, wbi::Integrator::implicit);
  EXPECT_EQ(c.mujoco.joint_friction, MujocoOptions::JointFriction::kTorque);

  // A configuration built in code is completed the same way, idempotently.
  RobotConfig in_code;
  in_code.urdf = humanoid_urdf();
  in_code.joints["l_knee"].armature = 0.5;
  complete_from_urdf(in_code);
  complete_from_urdf(in_code);
  EXPECT_EQ(in_code.joints.size(), 30u);
  EXPECT_EQ(in_code.joints.at("l_knee").armature, 0.5);
  EXPECT_EQ(in_code.contacts.size(), 2u);
}

// joint_torque_sensors: absent or all (every joint), none, or a list of joints.
TEST(RobotConfig, JointTorqueSensorsAllNoneOrListed) {
  using Which = JointTorqueSensors::Which;
  const RobotConfig absent = parse_robot_config(humanoid(""), "robot.yaml");
  EXPECT_EQ(absent.joint_torque_sensors.which, Which::kAll);
  EXPECT_TRUE(absent.joint_torque_sensors.has("l_knee"));
  const RobotConfig all = parse_robot_config(humanoid("joint_torque_sensors: all\n"), "robot.yaml");
  EXPECT_EQ(all.joint_torque_sensors.which, Which::kAll);
  const RobotConfig none =
      parse_robot_config(humanoid("joint_torque_sensors: none\n"), "robot.yaml");
  EXPECT_EQ(none.joint_torque_sensors.which, Which::kNone);
  EXPECT_FALSE(none.joint_torque_sensors.has("l_knee"));
  const RobotConfig listed =
      parse_robot_config(humanoid("joint_torque_sensors: [r_knee, l_knee]\n"), "robot.yaml");
  EXPECT_EQ(listed.joint_torque_sensors.which, Which::kListed);
  EXPECT_EQ(listed.joint_torque_sensors.joints, (std::vector<std::string>{"r_knee", "l_knee"}));
  EXPECT_TRUE(listed.joint_torque_sensors.has("l_knee"));
  EXPECT_FALSE(listed.joint_torque_sensors.has("l_hip_pitch"));
  const RobotConfig empty =
      parse_robot_config(humanoid("joint_torque_sensors: []\n"), "robot.yaml");
  EXPECT_FALSE(empty.joint_torque_sensors.has("l_knee")) << "an empty list is none";
}

TEST(RobotConfigErrors, JointTorqueSensors) {
  expect_error(humanoid("joint_torque_sensors: some\n"), 2, "joint_torque_sensors",
               "expected all, none or a list of joints, got 'some'");
  expect_error(humanoid("joint_torque_sensors: {l_knee: true}\n"), 2, "joint_torque_sensors",
               "expected all, none or a list of joints");
  expect_error(humanoid("joint_torque_sensors:\n  - l_knee\n  - [r_knee]\n"), 4,
               "joint_torque_sensors[1]", "expected a string");
  expect_error(humanoid("joint_torque_sensors: [l_knee, l_kne]\n"), 2, "joint_torque_sensors[1]",
               "unknown joint 'l_kne' (not a movable joint of ");
  expect_error(humanoid("joint_torque_sensors: [l_foot_ft_sensor]\n"), 2, "joint_torque_sensors[0]",
               "unknown joint 'l_foot_ft_sensor'");  // a fixed joint
  expect_error(humanoid("joint_torque_sensors:\n  - l_knee\n  - r_knee\n  - l_knee\n"), 5,
               "joint_torque_sensors[2]", "joint 'l_knee' given twice");
}

// ---- one test per error class ----

TEST(RobotConfigErrors, MissingUrdfFileNamesTheExpectedPath) {
  expect_error("# a robot\n\nurdf: ../../../shared/models/nobody/model.urdf\n", 3, "urdf",
               "../../../shared/models/nobody/model.urdf not found (the real robots' URDFs are "
               "expected in ../shared/models beside the repository");
  expect_error("urdf: /nonexistent/robot.urdf\n", 1, "urdf", "/nonexistent/robot.urdf not found");
  expect_error("fixed_base: true\n", 1, "urdf", "required");
  const std::string no_file = [] {
    try {
      load_robot_config("/nonexistent/robot.yaml");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_EQ(no_file, "/nonexistent/robot.yaml: cannot open the robot config file");
}

TEST(RobotConfigErrors, BadUrdfIsNamed) {
  const auto bad = std::filesystem::temp_directory_path() /
                   ("wbi_robot_config_bad_" + std::to_string(::getpid()) + ".urdf");
  std::ofstream(bad) << "<robot name='x'><link name='a'>\n";
  expect_error("urdf: " + bad.string() + "\n", 1, "urdf", bad.string());
  std::filesystem::remove(bad);
}

TEST(RobotConfigErrors, UnknownKey) {
  expect_error(humanoid("stepp: 0.001\n"), 2, "stepp", "unknown key (allowed: urdf, ");
  expect_error(humanoid("wbi:\n  contact: {stifness: 3}\n"), 3, "wbi.contact.stifness",
               "unknown key");
  expect_error(humanoid("contacts:\n  - {link: l_foot, sphere: {radius: 0.1}, pos: [0, 0, 0]}\n"),
               3, "contacts[0].pos", "unknown key");
  expect_error(humanoid("joints: {l_knee: {inertia: 1}}\n"), 2, "joints.l_knee.inertia",
               "unknown key (allowed: armature, damping, friction, kp, kd)");
  expect_error(humanoid("mujoco: {time_step: 0.001}\n"), 2, "mujoco.time_step", "unknown key");
}

TEST(RobotConfigErrors, KeyGivenTwiceOrNotAName) {
  expect_error(humanoid("ground: {height: 0}\nplace_on_ground: true\nground: {height: 1}\n"), 2,
               "ground", "given twice");
  expect_error(humanoid("joints:\n  l_knee: {armature: 0.1}\n  l_knee: {armature: 0.2}\n"), 3,
               "joints.l_knee", "given twice");
  expect_error(humanoid("initial_joint_positions: {[l_knee]: 0.3}\n"), 2, "initial_joint_positions",
               "a key must be a plain name");
}

TEST(RobotConfigErrors, WrongType) {
  expect_error(humanoid("wbi: {step: fast}\n"), 2, "wbi.step", "expected a number, got 'fast'");
  expect_error(humanoid("place_on_ground: maybe\n"), 2, "place_on_ground",
               "expected true or false");
  expect_error(humanoid("wbi: {substeps: 1.5}\n"), 2, "wbi.substeps", "expected an integer");
  expect_error(humanoid("ground: [0, 1]\n"), 2, "ground", "expected a map");
  expect_error(humanoid("imus: {name: imu}\n"), 2, "imus", "expected a list");
  expect_error(humanoid("initial_joint_positions: {l_knee: bent}\n"), 2,
               "initial_joint_positions.l_knee", "expected a number");
  expect_error(humanoid("mujoco: {integrator: RK5}\n"), 2, "mujoco.integrator",
               "expected one of Euler, implicit, RK4, got 'RK5'");
  expect_error(humanoid("mujoco: {cone: round}\n"), 2, "mujoco.cone", "pyramidal, elliptic");
  expect_error(humanoid("mujoco: {joint_friction: sticky}\n"), 2, "mujoco.joint_friction",
               "expected one of torque, constraint, got 'sticky'");
  expect_error(humanoid("wbi: {contact: {tangential: sticky}}\n"), 2, "wbi.contact.tangential",
               "sticky");
}

TEST(RobotConfigErrors, WrongVectorSize) {
  expect_error(humanoid("gravity: [0, 0]\n"), 2, "gravity", "expected a list of 3 numbers");
  expect_error(humanoid("initial_base_orientation: [1, 0, 0]\n"), 2, "initial_base_orientation",
               "4 numbers");
  expect_error(humanoid("contacts:\n  - {link: l_foot, box: {size: [0.2, 0.1]}}\n"), 3,
               "contacts[0].box.size", "3 numbers");
  expect_error(humanoid("mujoco:\n  solimp: [0.9, 0.95, 0.001]\n"), 3, "mujoco.solimp",
               "5 numbers");
}

TEST(RobotConfigErrors, NegativeOrOutOfRangeValues) {
  expect_error(humanoid("joints:\n  l_knee: {kd: -1}\n"), 3, "joints.l_knee.kd", "must be >= 0");
  expect_error(humanoid("joints:\n  default: {armature: -0.1}\n"), 3, "joints.default.armature",
               "must be >= 0");
  expect_error(humanoid("joints: {l_knee: {damping: -1}}\n"), 2, "joints.l_knee.damping",
               "must be >= 0");
  expect_error(humanoid("ground: {friction: -0.2}\n"), 2, "ground.friction", "must be >= 0");
  expect_error(humanoid("contacts: [{link: l_foot, sphere: {radius: 0}}]\n"), 2,
               "contacts[0].sphere.radius", "must be > 0");
  expect_error(humanoid("contacts: [{link: l_foot, box: {size: [0.2, -0.1, 0.01]}}]\n"), 2,
               "contacts[0].box.size", "must be > 0");
  expect_error(humanoid("wbi: {step: -1}\n"), 2, "wbi.step", "must be > 0");
  expect_error(humanoid("wbi: {substeps: 0}\n"), 2, "wbi.substeps", "must be >= 1");
  expect_error(humanoid("mujoco: {impratio: 0}\n"), 2, "mujoco.impratio", "must be > 0");
  expect_error(humanoid("mujoco: {solref: [0.02, -1]}\n"), 2, "mujoco.solref", "timeconst");
  expect_error(humanoid("mujoco: {solimp: [0.9, 1.5, 0.001, 0.5, 2]}\n"), 2, "mujoco.solimp",
               "dmax in (0, 1)");
  expect_error(humanoid("initial_base_orientation: [0, 0, 0, 0]\n"), 2, "initial_base_orientation",
               "non-zero");
}

TEST(RobotConfigErrors, UnknownJoint) {
  expect_error(humanoid("initial_joint_positions:\n  l_kne: 0.3\n"), 3,
               "initial_joint_positions.l_kne", "unknown joint 'l_kne'");
  expect_error(humanoid("joints:\n  default: {damping: 1}\n  r_kne: {armature: 0.1}\n"), 4,
               "joints.r_kne", "unknown joint 'r_kne'");
  // a fixed joint is not a joint of the model
  expect_error(humanoid("joints: {l_foot_ft_sensor: {armature: 0.1}}\n"), 2,
               "joints.l_foot_ft_sensor", "not a movable joint");
}

TEST(RobotConfigErrors, UnknownLinkOrFrame) {
  expect_error(humanoid("contacts:\n  - {link: left_foot, sphere: {radius: 0.1}}\n"), 3,
               "contacts[0].link", "unknown link or frame 'left_foot'");
  expect_error(humanoid("imus:\n  - {name: imu, frame: imu_fram}\n"), 3, "imus[0].frame",
               "unknown link or frame 'imu_fram'");
  expect_error(humanoid("pushes:\n  - {link: torso, force: [1, 0, 0]}\n"), 3, "pushes[0].link",
               "'torso'");
  expect_error(humanoid("imus: [{name: imu}]\n"), 2, "imus[0].frame", "required");
}

TEST(RobotConfigErrors, ForceTorqueJointMustBeAFixedJoint) {
  expect_error(humanoid("force_torque:\n  - {name: l_ft, joint: l_knee}\n"), 3,
               "force_torque[0].joint", "'l_knee' is not a fixed joint");
  expect_error(humanoid("force_torque:\n  - {name: l_ft, joint: l_foot_ft}\n"), 3,
               "force_torque[0].joint", "unknown joint 'l_foot_ft'");
}

TEST(RobotConfigErrors, ContactNeedsExactlyOneShape) {
  expect_error(humanoid("contacts:\n  - {link: l_foot}\n"), 3, "contacts[0]",
               "expected exactly one of box, sphere, capsule");
  expect_error(humanoid("contacts:\n  - {link: l_foot, sphere: {radius: 0.1}, box: {size: [1, "
                        "1, 1]}}\n"),
               3, "contacts[0]", "exactly one");
  expect_error(humanoid("contacts:\n  - {link: l_foot, capsule: {radius: 0.1}}\n"), 3,
               "contacts[0].capsule", "'radius' and 'length' are required");
}

TEST(RobotConfigErrors, YamlSyntaxHasItsLine) {
  expect_error(humanoid("gravity: [0, 0,\n"), 3, "yaml", "");
  const std::string message = error_of(humanoid("ground: {height: 0\n  friction: [\n"));
  EXPECT_EQ(message.rfind("robot.yaml:", 0), 0u) << message;
}

}  // namespace
}  // namespace wbi::robot_config
