// The robot config files of deploy/robots load and validate, and their soles are
// where the sole frames are. The real robots' URDFs are used by path only from
// ../shared/models; without it their tests are skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <tuple>

#include <Eigen/Geometry>

#include "test_support.hpp"
#include "wbi/model/data.hpp"
#include "wbi/model/kinematics.hpp"
#include "wbi/model/urdf.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::robot_config {
namespace {

std::string robot_file(const std::string& name) {
  return (wbi::test::source_dir() / "deploy" / "robots" / name).string();
}

// The file of a real robot, or "" when ../shared is missing.
std::string real_robot_file(const std::string& name, const std::string& urdf) {
  const auto shared = wbi::test::shared_models_dir();
  if (!shared || !std::filesystem::exists(*shared / urdf)) {
    return "";
  }
  return robot_file(name);
}

// Pose of a frame in the world at the config's initial posture (base at the origin).
struct Pose {
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
};
Pose frame_pose(const model::Model& m, model::Data& d, const RobotConfig& c,
                const std::string& frame) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.nq);
  if (m.floating_base) {
    q[3] = 1.0;
  }
  for (const auto& [name, value] : c.initial_joint_positions) {
    q[m.base_nq + m.joint_id(name)] = value;
  }
  model::forward_kinematics(m, d, q);
  const auto fi = static_cast<std::size_t>(m.frame_id(frame));
  const auto b = static_cast<std::size_t>(m.frame_body[fi]);
  return {d.R_WB[b] * m.frame_R_BF[fi], d.p_WB[b] + d.R_WB[b] * m.frame_p_BF[fi]};
}

// Every box of `links` has its bottom face (−z) at the z of `sole`, and at the
// initial posture the sole lies flat (its z axis up).
void expect_soles_at(const RobotConfig& c, const std::vector<std::string>& links,
                     const std::string& sole) {
  const model::Model m = model::load_urdf_file(c.urdf);
  model::Data d(m);
  const Pose S = frame_pose(m, d, c, sole);
  EXPECT_GT(S.R.col(2).z(), 0.99999) << sole << " is not flat at the initial posture";
  for (const auto& g : c.contacts) {
    if (std::find(links.begin(), links.end(), g.link) == links.end()) {
      continue;
    }
    ASSERT_EQ(g.shape, wbi::ContactShape::box) << g.link;
    const Pose L = frame_pose(m, d, c, g.link);
    const Eigen::Vector3d bottom_L =
        g.position + g.rotation * Eigen::Vector3d(0, 0, -0.5 * g.size.z());
    const Eigen::Vector3d bottom_S = S.R.transpose() * (L.p + L.R * bottom_L - S.p);
    EXPECT_NEAR(bottom_S.z(), 0.0, 1e-4) << g.link << " bottom face vs " << sole;
  }
}

TEST(RobotFiles, Arm) {
  const RobotConfig c = load_robot_config(robot_file("arm.yaml"));
  EXPECT_EQ(c.joints.size(), 7u);
  EXPECT_TRUE(c.contacts.empty());
  EXPECT_EQ(c.initial_joint_positions.at("joint_4"), 1.6);
  EXPECT_EQ(c.wbi.step, 0.001);
}

TEST(RobotFiles, Humanoid) {
  const RobotConfig c = load_robot_config(robot_file("humanoid.yaml"));
  EXPECT_EQ(c.joints.size(), 30u);
  ASSERT_EQ(c.contacts.size(), 2u);
  EXPECT_EQ(c.force_torque.size(), 2u);
  EXPECT_EQ(c.imus.size(), 1u);
  expect_soles_at(c, {"l_foot"}, "l_sole");
  expect_soles_at(c, {"r_foot"}, "r_sole");
}

TEST(RobotFiles, Icub3) {
  const std::string file = real_robot_file("icub3.yaml", "iCubGenova09/model.urdf");
  if (file.empty()) {
    GTEST_SKIP() << wbi::test::kSharedMissing
                 << " (expected ../shared/models/iCubGenova09/model.urdf)";
  }
  const RobotConfig c = load_robot_config(file);
  EXPECT_EQ(c.joints.size(), 32u);
  for (const auto& [name, joint] : c.joints) {
    EXPECT_GT(joint.armature, 0.0) << name;
  }
  EXPECT_EQ(c.contacts.size(), 4u);
  EXPECT_EQ(c.force_torque.size(), 8u);
  EXPECT_EQ(c.imus.size(), 2u);
  // As the real robot: no joint-torque sensors (torques come from the F/T sensors).
  EXPECT_EQ(c.joint_torque_sensors.which, JointTorqueSensors::Which::kNone);
  expect_soles_at(c, {"l_foot_front", "l_foot_rear"}, "l_sole");
  expect_soles_at(c, {"r_foot_front", "r_foot_rear"}, "r_sole");
}

TEST(RobotFiles, Talos) {
  const std::string file = real_robot_file("talos.yaml", "talos/talos_reduced.urdf");
  if (file.empty()) {
    GTEST_SKIP() << wbi::test::kSharedMissing
                 << " (expected ../shared/models/talos/talos_reduced.urdf)";
  }
  const RobotConfig c = load_robot_config(file);
  EXPECT_EQ(c.joints.size(), 32u);
  EXPECT_EQ(c.joints.at("leg_left_4_joint").armature, 0.1);
  EXPECT_EQ(c.joints.at("leg_left_4_joint").friction, 2.0);
  EXPECT_EQ(c.joints.at("arm_left_1_joint").damping, 1.0);  // the URDF's
  EXPECT_EQ(c.contacts.size(), 2u);
  EXPECT_EQ(c.force_torque.size(), 4u);
  expect_soles_at(c, {"left_sole_link"}, "left_sole_link");
  expect_soles_at(c, {"right_sole_link"}, "right_sole_link");
}

// The fixed-base variants (deploy/icub3_pd.yaml, talos_pd.yaml) repeat their
// standing robot's joint dynamics: they must move as it does.
TEST(RobotFiles, FixedBaseVariantsHaveTheStandingRobotsJoints) {
  for (const auto& [standing, fixed, urdf] :
       {std::tuple{"icub3.yaml", "icub3_fixed_base.yaml", "iCubGenova09/model.urdf"},
        std::tuple{"talos.yaml", "talos_fixed_base.yaml", "talos/talos_reduced.urdf"}}) {
    const std::string standing_file = real_robot_file(standing, urdf);
    if (standing_file.empty()) {
      GTEST_SKIP() << wbi::test::kSharedMissing << " (expected ../shared/models/" << urdf << ")";
    }
    const RobotConfig a = load_robot_config(standing_file);
    const RobotConfig b = load_robot_config(robot_file(fixed));
    EXPECT_FALSE(a.fixed_base) << standing;
    EXPECT_TRUE(b.fixed_base) << fixed;
    ASSERT_EQ(a.joints.size(), b.joints.size()) << fixed;
    EXPECT_EQ(a.joint_torque_sensors.which, b.joint_torque_sensors.which) << fixed;
    EXPECT_EQ(a.joint_torque_sensors.joints, b.joint_torque_sensors.joints) << fixed;
    for (const auto& [name, joint] : a.joints) {
      const auto& other = b.joints.at(name);
      EXPECT_EQ(joint.armature, other.armature) << fixed << ": " << name;
      EXPECT_EQ(joint.damping, other.damping) << fixed << ": " << name;
      EXPECT_EQ(joint.friction, other.friction) << fixed << ": " << name;
      EXPECT_EQ(joint.kp, other.kp) << fixed << ": " << name;
      EXPECT_EQ(joint.kd, other.kd) << fixed << ": " << name;
    }
  }
}

// A real robot's file whose ../shared is missing fails with one line naming the
// expected path (simulated by parsing the same text from a directory without it).
TEST(RobotFiles, MissingSharedNamesTheExpectedPath) {
  const auto elsewhere = std::filesystem::temp_directory_path() / "wbi_no_shared" / "a" / "b";
  try {
    parse_robot_config("urdf: ../../../shared/models/iCubGenova09/model.urdf\n",
                       (elsewhere / "icub3.yaml").string());
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind((elsewhere / "icub3.yaml").string() +
                             ":1: urdf: ../../../shared/models/iCubGenova09/model.urdf not found",
                         0),
              0u)
        << what;
    EXPECT_NE(what.find("expected in ../shared/models beside the repository"), std::string::npos);
  }
}

}  // namespace
}  // namespace wbi::robot_config
