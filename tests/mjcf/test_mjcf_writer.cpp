// wbi::mjcf::write_mjcf without MuJoCo: what is written (every number exactly,
// the base, names, sensors), every bad option as one clear error, and
// LoadOptions::repair_inertia (which links, what it makes of them, nothing else).
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include <tinyxml2.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <wbi/mjcf/mjcf.hpp>
#include <wbi/model/urdf.hpp>

#include "test_support.hpp"

namespace {

namespace wm = wbi::model;
namespace wj = wbi::mjcf;

// A floating body "a" with a moving child "c" whose inertia breaks the triangle
// inequality (1 + 1 < 5, ×1e-3), and a fixed child "b" of c.
const char* kBadInertiaUrdf = R"(<?xml version="1.0"?>
<robot name="bad">
  <link name="a">
    <inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="2"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.25"/></inertial>
  </link>
  <joint name="a_to_c" type="revolute">
    <parent link="a"/><child link="c"/><origin xyz="0 0 0.3" rpy="0.1 0.2 0.3"/><axis xyz="1 0 0"/>
    <limit lower="-1.5" upper="2.0" effort="12" velocity="3"/>
  </joint>
  <link name="c">
    <inertial><origin xyz="0 0 0.1" rpy="0.5 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.005"/></inertial>
  </link>
  <joint name="c_to_b" type="fixed">
    <parent link="c"/><child link="b"/><origin xyz="0 0 0.2" rpy="0 0 0"/>
  </joint>
  <link name="b"/>
</robot>)";

wm::Model humanoid() { return wm::load_urdf_file(wbi::test::project_model("humanoid.urdf")); }

std::string error_of(const wm::Model& model, const wj::MjcfOptions& options) {
  try {
    wj::write_mjcf(model, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

const tinyxml2::XMLElement* find(const tinyxml2::XMLElement* e, const char* tag,
                                 const std::string& name) {
  for (; e != nullptr; e = e->NextSiblingElement()) {
    if (std::string(e->Name()) == tag && e->Attribute("name") != nullptr &&
        name == e->Attribute("name")) {
      return e;
    }
    if (const auto* inner = find(e->FirstChildElement(), tag, name)) {
      return inner;
    }
  }
  return nullptr;
}

Eigen::VectorXd numbers(const char* text) {
  std::vector<double> v;
  char* end = nullptr;
  for (const char* p = text; *p != '\0'; p = end) {
    v.push_back(std::strtod(p, &end));
    if (end == p) {
      break;
    }
  }
  return Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

TEST(MjcfWriter, NumbersReadBackExactly) {
  const wm::Model model = humanoid();
  const std::string xml = wj::write_mjcf(model);
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS);
  for (int b = 1; b < model.n_bodies; ++b) {
    const auto ub = static_cast<std::size_t>(b);
    const auto* body = find(doc.RootElement(), "body", model.body_name[ub]);
    ASSERT_NE(body, nullptr) << model.body_name[ub];
    EXPECT_EQ(numbers(body->Attribute("pos")), Eigen::VectorXd(model.joint_p_PJ[ub]))
        << model.body_name[ub];
    const auto* inertial = body->FirstChildElement("inertial");
    ASSERT_NE(inertial, nullptr);
    EXPECT_EQ(numbers(inertial->Attribute("mass"))[0], model.body_mass[ub]);
    EXPECT_EQ(numbers(inertial->Attribute("pos")), Eigen::VectorXd(model.body_com[ub]));
    // principal moments and axes put back together give the inertia to rounding
    const Eigen::VectorXd d = numbers(inertial->Attribute("diaginertia"));
    const Eigen::VectorXd qv = numbers(inertial->Attribute("quat"));
    const Eigen::Matrix3d R = Eigen::Quaterniond(qv[0], qv[1], qv[2], qv[3]).toRotationMatrix();
    const Eigen::Matrix3d I = R * d.asDiagonal() * R.transpose();
    EXPECT_LE((I - model.body_inertia_c[ub]).cwiseAbs().maxCoeff(),
              1e-15 * model.body_inertia_c[ub].norm())
        << model.body_name[ub];
  }
}

TEST(MjcfWriter, FreeJointOnTheRootLinkWhenFloatingNoneWhenFixed) {
  const wm::Model model = humanoid();
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(wj::write_mjcf(model).c_str()), tinyxml2::XML_SUCCESS);
  const auto* root = doc.RootElement()->FirstChildElement("worldbody")->FirstChildElement("body");
  ASSERT_NE(root, nullptr);
  EXPECT_EQ(std::string(root->Attribute("name")), model.body_name[0]);
  EXPECT_EQ(std::string(root->Attribute("pos")), "0 0 0");
  const auto* joint = root->FirstChildElement("joint");
  ASSERT_NE(joint, nullptr);
  EXPECT_EQ(std::string(joint->Attribute("type")), "free");
  EXPECT_EQ(std::string(joint->Attribute("name")), "floating_base");

  wj::MjcfOptions fixed;
  fixed.floating_base = false;
  const std::string xml = wj::write_mjcf(model, fixed);
  EXPECT_EQ(xml.find("type=\"free\""), std::string::npos);

  // a fixed root named "world" is MuJoCo's world body; its mass goes on a welded body
  const wm::Model arm = wm::load_urdf_file(wbi::test::project_model("arm7.urdf"));
  ASSERT_EQ(arm.body_name[0], "world");
  const std::string arm_xml = wj::write_mjcf(arm);
  EXPECT_EQ(arm_xml.find("<body name=\"world\""), std::string::npos);
  EXPECT_EQ(arm_xml.find("type=\"free\""), std::string::npos);
}

TEST(MjcfWriter, OptionsSitesSensorsContactsAndGround) {
  const wm::Model model = humanoid();
  wj::MjcfOptions options;
  options.timestep = 0.0005;
  options.integrator = wbi::Integrator::rk4;
  options.ground.enabled = true;
  options.ground.friction = 0.8;
  options.sites.push_back(
      {"imu", "imu_frame", {}, Eigen::Matrix3d::Identity(), wj::SiteSensor::kImu});
  options.sites.push_back(
      {"l_ft", "l_foot", {}, Eigen::Matrix3d::Identity(), wj::SiteSensor::kForceTorque});
  wj::ContactGeometry sole;
  sole.name = "l_sole_box";
  sole.link = "l_sole";
  sole.size = {0.2, 0.1, 0.02};
  options.contacts.push_back(sole);
  wj::ContactGeometry heel;
  heel.link = "r_sole";
  heel.shape = wbi::ContactShape::capsule;
  heel.radius = 0.02;
  heel.length = 0.1;
  options.contacts.push_back(heel);
  const std::string xml = wj::write_mjcf(model, options);
  for (const char* expected :
       {"timestep=\"5e-04\"", "integrator=\"RK4\"", "<geom name=\"ground\" type=\"plane\"",
        "friction=\"0.8 0.005 1e-04\"", "<site name=\"imu\"", "<site name=\"l_ft\"",
        "<force name=\"l_ft_force\" site=\"l_ft\"/>",
        "<torque name=\"l_ft_torque\" site=\"l_ft\"/>",
        "<framequat name=\"imu_quat\" objtype=\"site\" objname=\"imu\"/>",
        "<gyro name=\"imu_gyro\" site=\"imu\"/>",
        "<accelerometer name=\"imu_accelerometer\" site=\"imu\"/>",
        "<geom name=\"l_sole_box\" type=\"box\" size=\"0.1 0.05 0.01\"",
        "<geom name=\"r_sole_contact_1\" type=\"capsule\" size=\"0.02 0.05\"",
        "inertiafromgeom=\"false\"", "angle=\"radian\""}) {
    EXPECT_NE(xml.find(expected), std::string::npos) << expected;
  }
}

TEST(MjcfWriter, BadOptionsAreOneClearError) {
  const wm::Model model = humanoid();
  const std::string joint = model.joint_name[2];
  auto with = [&](auto change) {
    wj::MjcfOptions options;
    change(options);
    return error_of(model, options);
  };
  const auto n = static_cast<std::size_t>(model.n_joints);
  EXPECT_EQ(with([](wj::MjcfOptions& o) {
              o.armature = {0.1, 0.2, 0.3};
            }),
            "MJCF: armature: 3 values for " + std::to_string(n) +
                " joints (one per joint, in the model's order)");
  EXPECT_EQ(with([&](wj::MjcfOptions& o) {
              o.damping.assign(n, 0.1);
              o.damping[2] = -1.0;
            }),
            "MJCF: damping of joint '" + joint + "' is -1, expected a finite value >= 0");
  EXPECT_EQ(with([&](wj::MjcfOptions& o) {
              o.frictionloss.assign(n, 0.1);
              o.frictionloss[2] = std::numeric_limits<double>::quiet_NaN();
            }),
            "MJCF: frictionloss of joint '" + joint + "' is nan, expected a finite value >= 0");
  EXPECT_EQ(with([](wj::MjcfOptions& o) { o.timestep = 0.0; }),
            "MJCF: timestep must be > 0, got 0");
  EXPECT_EQ(with([&](wj::MjcfOptions& o) { o.free_joint_name = joint; }),
            "MJCF: free_joint_name '" + joint + "' is a joint of the model");
  EXPECT_EQ(with([](wj::MjcfOptions& o) {
              wj::ContactGeometry g;
              g.link = "nope";
              g.size = {1, 1, 1};
              o.contacts.push_back(g);
            }),
            "MJCF: contact 0 ('nope_contact_0'): unknown link 'nope'");
  EXPECT_EQ(with([](wj::MjcfOptions& o) {
              wj::ContactGeometry g;
              g.link = "l_sole";
              g.shape = wbi::ContactShape::sphere;
              o.contacts.push_back(g);
            }),
            "MJCF: contact 0 ('l_sole_contact_0'): a box needs size > 0 in x, y, z; a sphere "
            "radius > 0; a capsule radius and length > 0");
  EXPECT_EQ(with([](wj::MjcfOptions& o) {
              wj::ContactGeometry g;
              g.name = "ground";
              g.link = "l_sole";
              g.size = {1, 1, 1};
              o.contacts.push_back(g);
            }),
            "MJCF: contact 0 ('ground'): geom name used twice");
  EXPECT_EQ(with([](wj::MjcfOptions& o) {
              o.sites.push_back({"s", "l_sole", {}, Eigen::Matrix3d::Identity(), {}});
              o.sites.push_back({"s", "r_sole", {}, Eigen::Matrix3d::Identity(), {}});
            }),
            "MJCF: site 's': empty or used twice");
  EXPECT_EQ(with([](wj::MjcfOptions& o) {
              o.sites.push_back({"s", "nowhere", {}, Eigen::Matrix3d::Identity(), {}});
            }),
            "MJCF: site 's': unknown frame 'nowhere'");
  EXPECT_EQ(with([](wj::MjcfOptions& o) { o.welded_links = {"nope"}; }),
            "MJCF: welded_links: unknown link 'nope'");
  EXPECT_EQ(with([&](wj::MjcfOptions& o) { o.welded_links = {model.body_name[3]}; }),
            "MJCF: welded_links: link '" + model.body_name[3] +
                "' is already a body of its own (a joint moves it, or it is the root)");
  EXPECT_EQ(with([](wj::MjcfOptions& o) {
              o.welded_links = {"l_foot", "l_foot"};
            }),
            "MJCF: welded_links: link 'l_foot' is listed twice");
}

// MuJoCo's own inertia checks, made before MuJoCo sees the file.
TEST(MjcfWriter, InertiasMuJoCoWouldRejectAreNamed) {
  const wm::Model bad = wm::load_urdf_string(kBadInertiaUrdf);
  EXPECT_TRUE(bad.repaired_inertia_links.empty());
  const std::string error = error_of(bad, {});
  EXPECT_NE(error.find("MJCF: body 'c': principal moments of inertia ("), std::string::npos)
      << error;
  EXPECT_NE(error.find("break the triangle inequality A + B >= C"), std::string::npos) << error;
  EXPECT_NE(error.find("LoadOptions::repair_inertia"), std::string::npos) << error;

  // a moving body without mass
  std::string massless = kBadInertiaUrdf;
  const auto from = massless.find("<link name=\"c\">");
  const auto to = massless.find("</link>", from);
  massless.replace(from, to - from, "<link name=\"c\">");
  const std::string message = error_of(wm::load_urdf_string(massless), {});
  EXPECT_NE(message.find("MJCF: body 'c' moves but has mass 0"), std::string::npos) << message;
}

// The per-link data the loader keeps for splitting bodies again.
TEST(ModelFrames, ParentJointAndInertiaOfEveryLink) {
  const wm::Model model = humanoid();
  const int foot = model.frame_id("l_foot");
  EXPECT_EQ(model.frame_joint[static_cast<std::size_t>(foot)], "l_foot_ft_sensor");
  EXPECT_EQ(
      model
          .frame_name[static_cast<std::size_t>(model.frame_parent[static_cast<std::size_t>(foot)])],
      "l_ankle_2");
  EXPECT_EQ(model.frame_joint[0], "");
  EXPECT_EQ(model.frame_parent[0], -1);
  for (int b = 0; b < model.n_bodies; ++b) {
    wm::SpatialInertia sum;
    for (int f = 0; f < model.n_frames(); ++f) {
      if (model.frame_body[static_cast<std::size_t>(f)] == b) {
        sum += model.frame_inertia[static_cast<std::size_t>(f)];
      }
    }
    EXPECT_EQ(sum.m, model.body_inertia[b].m);
    EXPECT_EQ(sum.h, model.body_inertia[b].h);
    EXPECT_EQ(sum.I, model.body_inertia[b].I);
  }
}

// -------------------------------------------------- LoadOptions::repair_inertia

TEST(RepairInertia, NearestPhysicalInertiaKeepsAxesMassAndCom) {
  wm::LoadOptions repair;
  repair.repair_inertia = true;
  const wm::Model plain = wm::load_urdf_string(kBadInertiaUrdf);
  const wm::Model model = wm::load_urdf_string(kBadInertiaUrdf, repair);
  ASSERT_EQ(model.repaired_inertia_links, std::vector<std::string>{"c"});
  const int c = model.body_id("c");
  EXPECT_EQ(model.body_mass[c], plain.body_mass[c]);
  EXPECT_EQ(model.body_com[c], plain.body_com[c]);
  // λ = (1, 1, 5)e-3: σ = Σλ/2 − λ = (2.5, 2.5, −1.5)e-3; σ3 → 1e-9 Σσ = 3.5e-12,
  // so λ' = Σσ' − σ' = (2.5e-3 + 3.5e-12, 2.5e-3 + 3.5e-12, 5e-3), same axes
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d expected =
      R * Eigen::Vector3d(2.5e-3 + 3.5e-12, 2.5e-3 + 3.5e-12, 5e-3).asDiagonal() * R.transpose();
  EXPECT_LE((model.body_inertia_c[c] - expected).cwiseAbs().maxCoeff(), 1e-17);
  const Eigen::Vector3d d =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(model.body_inertia_c[c]).eigenvalues();
  EXPECT_GT(d[0] + d[1] - d[2], 1e-12);  // strictly inside: MuJoCo's check has no tolerance
  EXPECT_NO_THROW(wj::write_mjcf(model));
}

TEST(RepairInertia, PhysicalInertiasAreUntouchedBitForBit) {
  wm::LoadOptions repair;
  repair.repair_inertia = true;
  const auto path = wbi::test::project_model("humanoid.urdf").string();
  const wm::Model plain = wm::load_urdf_file(path);
  const wm::Model model = wm::load_urdf_file(path, repair);
  EXPECT_TRUE(model.repaired_inertia_links.empty());
  for (int b = 0; b < model.n_bodies; ++b) {
    EXPECT_EQ(model.body_inertia_c[b], plain.body_inertia_c[b]);
  }
}

TEST(RepairInertia, TalosGrippersAreTheLinksRepaired) {
  const auto shared = wbi::test::shared_models_dir();
  if (!shared) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  const auto path = (*shared / "talos/talos_reduced.urdf").string();
  wm::LoadOptions repair;
  repair.repair_inertia = true;
  EXPECT_EQ(wm::load_urdf_file(path, repair).repaired_inertia_links,
            (std::vector<std::string>{"gripper_left_motor_single_link",
                                      "gripper_right_motor_single_link"}));
  EXPECT_TRUE(wm::load_urdf_file(path).repaired_inertia_links.empty());
  // strict_inertia rejects them; with repair_inertia as well, they are repaired
  wm::LoadOptions strict;
  strict.strict_inertia = true;
  EXPECT_THROW(wm::load_urdf_file(path, strict), std::invalid_argument);
  strict.repair_inertia = true;
  EXPECT_EQ(wm::load_urdf_file(path, strict).repaired_inertia_links.size(), 2U);
}

}  // namespace
