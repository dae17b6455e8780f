// info_json / write_info_text / joint_type_name on the project's arm (fixed base,
// lumped end effector), humanoid (floating) and double pendulum (continuous joint).
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>

#include <wbi/model/urdf.hpp>
#include <wbi/model_inspect/info_report.hpp>

#include "test_support.hpp"

namespace wm = wbi::model;
namespace inspect = wbi::model_inspect;
using nlohmann::json;

namespace {

wm::Model load(const char* file, wm::LoadOptions options = {}) {
  return wm::load_urdf_file(wbi::test::project_model(file).string(), options);
}

}  // namespace

TEST(InfoReport, ArmIsFixedWithSevenRevoluteJointsAndItsFramesOnItsBodies) {
  const wm::Model arm = load("arm7.urdf");
  const json info = inspect::info_json(arm);
  EXPECT_EQ(info["base"], "fixed");  // massless root 'world'
  EXPECT_EQ(info["root_link"], "world");
  EXPECT_EQ(info["nq"], 7);
  EXPECT_EQ(info["nv"], 7);
  ASSERT_EQ(info["joints"].size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) {
    const json& joint = info["joints"][k];
    EXPECT_EQ(joint["name"], "joint_" + std::to_string(k + 1));
    EXPECT_EQ(joint["type"], "revolute");
    EXPECT_EQ(joint["body"], "link_" + std::to_string(k + 1));
    EXPECT_EQ(joint["parent_body"], k == 0 ? "world" : "link_" + std::to_string(k));
    EXPECT_LT(joint["lower"].get<double>(), joint["upper"].get<double>());
    EXPECT_FALSE(joint.contains("mimic"));
  }
  // Bodies after lumping: the root and one per moving joint; every frame is on
  // exactly one body, and the masses add up to the total.
  ASSERT_EQ(info["bodies"].size(), 8u);
  EXPECT_TRUE(info["bodies"][0]["parent"].is_null());
  double mass = 0.0;
  std::multiset<std::string> listed;
  for (const json& body : info["bodies"]) {
    mass += body["mass"].get<double>();
    EXPECT_EQ(body["com"].size(), 3u);
    for (const json& frame : body["frames"]) {
      listed.insert(frame.get<std::string>());
    }
  }
  EXPECT_NEAR(mass, info["total_mass"].get<double>(), 1e-12);
  EXPECT_EQ(listed.size(), info["frames"].size());
  EXPECT_EQ(std::set<std::string>(listed.begin(), listed.end()).size(), listed.size());
  EXPECT_EQ(listed.count("tool_frame"), 1u);
  for (const json& frame : info["frames"]) {
    if (frame["name"] == "tool_frame") {
      EXPECT_EQ(frame["body"], "link_7");  // lumped into the last link
    }
  }
  EXPECT_TRUE(info["locked_joints"].empty());
}

TEST(InfoReport, HumanoidFloatsAndAReducedModelListsItsLockedJoints) {
  const wm::Model humanoid = load("humanoid.urdf");
  const json info = inspect::info_json(humanoid);
  EXPECT_EQ(info["base"], "floating");
  EXPECT_EQ(info["nq"].get<int>(), humanoid.n_joints + 7);
  EXPECT_EQ(info["nv"].get<int>(), humanoid.n_joints + 6);

  wm::LoadOptions reduced;
  reduced.joints = {humanoid.joint_name[2], humanoid.joint_name[0]};
  const json small = inspect::info_json(load("humanoid.urdf", reduced));
  ASSERT_EQ(small["joints"].size(), 2u);
  EXPECT_EQ(small["joints"][0]["name"], humanoid.joint_name[2]);
  EXPECT_EQ(small["locked_joints"].size(), static_cast<std::size_t>(humanoid.n_joints - 2));
  EXPECT_EQ(small["locked_joints"][0]["position"], 0.0);
}

TEST(InfoReport, ContinuousJointsHaveNullLimitsAndTheirOwnTypeName) {
  const wm::Model pendulum = load("double_pendulum.urdf");
  const int k = pendulum.joint_id("joint2");
  EXPECT_EQ(inspect::joint_type_name(pendulum, k), "continuous");
  const json joint = inspect::info_json(pendulum)["joints"][static_cast<std::size_t>(k)];
  EXPECT_TRUE(joint["lower"].is_null());
  EXPECT_TRUE(joint["upper"].is_null());
}

TEST(InfoReport, TextHasOneLinePerJointAndBodyAndShowsArmature) {
  wm::LoadOptions options;
  options.armature = {{"joint_3", 0.25}};
  const wm::Model arm = load("arm7.urdf", options);
  std::ostringstream text;
  inspect::write_info_text(text, arm);
  const std::string out = text.str();
  EXPECT_NE(out.find("base:       fixed (root link 'world')\n"), std::string::npos);
  EXPECT_NE(out.find("nq = 7, nv = 7, 7 joints, 8 bodies"), std::string::npos);
  std::istringstream lines(out);
  std::string line;
  int joint_lines = 0;
  int body_lines = 0;
  while (std::getline(lines, line)) {
    joint_lines += line.find("  vel ") != std::string::npos ? 1 : 0;
    body_lines += line.find(" mass ") != std::string::npos ? 1 : 0;
    if (line.find("joint_3 ") != std::string::npos) {
      EXPECT_NE(line.find("armature 0.25"), std::string::npos) << line;
    }
  }
  EXPECT_EQ(joint_lines, 7);
  EXPECT_EQ(body_lines, 8);
}
