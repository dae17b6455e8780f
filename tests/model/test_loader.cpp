// URDF loading: structure, lumping of fixed joints, frames, base kind, limits,
// mimic policy, reduced models, and clear errors on bad input.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "model_test_common.hpp"
#include "reference.hpp"

namespace wm = wbi::model;
using wbi::test::near_rel;

namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

// Two boxes joined by a fixed joint, then a revolute joint to a third link.
const char* kLumpUrdf = R"(<?xml version="1.0"?>
<robot name="lump">
  <link name="a">
    <inertial><origin xyz="0.1 0 0" rpy="0 0 0"/><mass value="2"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/></inertial>
  </link>
  <joint name="a_to_b" type="fixed">
    <parent link="a"/><child link="b"/><origin xyz="0 0.5 0" rpy="0 0 1.5707963267948966"/>
  </joint>
  <link name="b">
    <inertial><origin xyz="0.2 0 0" rpy="0 0 0"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial>
  </link>
  <joint name="b_to_c" type="revolute">
    <parent link="b"/><child link="c"/><origin xyz="0 0 0.3" rpy="0 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-1.5" upper="2.0" effort="12" velocity="3"/>
  </joint>
  <link name="c">
    <inertial><origin xyz="0 0 0.1" rpy="0 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <joint name="c_to_marker" type="fixed">
    <parent link="c"/><child link="marker"/><origin xyz="0 0 0.2" rpy="0 0 0"/>
  </joint>
  <link name="marker"/>
  <gazebo reference="c"><material>Gazebo/Red</material></gazebo>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type></transmission>
</robot>)";

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("wbi_model_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

// Expects load_urdf_file(text) to throw an error whose message contains every word.
void expect_load_error(const std::string& name, const std::string& text,
                       const std::vector<std::string>& words, const wm::LoadOptions& options = {}) {
  const std::string path = write_temp(name, text);
  try {
    (void)wm::load_urdf_file(path, options);
    ADD_FAILURE() << name << ": no error";
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << "message does not name the file: " << msg;
    for (const auto& w : words) {
      EXPECT_NE(msg.find(w), std::string::npos) << name << ": '" << w << "' not in: " << msg;
    }
  }
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) {
    s.replace(pos, from.size(), to);
  }
  return s;
}

}  // namespace

TEST(Loader, LumpsFixedJointsExactly) {
  const wm::Model model = wm::load_urdf_string(kLumpUrdf);
  EXPECT_TRUE(model.floating_base);
  EXPECT_EQ(model.n_bodies, 2);
  EXPECT_EQ(model.n_joints, 1);
  EXPECT_EQ(model.nq, 8);
  EXPECT_EQ(model.nv, 7);
  EXPECT_EQ(model.n_frames(), 4);  // every link is a frame, the massless marker too
  EXPECT_DOUBLE_EQ(model.total_mass, 3.5);
  // body 0 = a + b: b's CoM is at (0, 0.5, 0) + Rz(90°)(0.2, 0, 0) = (0, 0.7, 0)
  EXPECT_DOUBLE_EQ(model.body_mass[0], 3.0);
  EXPECT_TRUE(model.body_com[0].isApprox(Eigen::Vector3d(2 * 0.1 / 3, 0.7 / 3, 0), 1e-15));
  // inertia about the lumped CoM: parallel-axis theorem, b rotated by 90° about z
  const Eigen::Vector3d c = model.body_com[0];
  const Eigen::Vector3d ca(0.1, 0, 0), cb(0, 0.7, 0);
  auto shift = [](double m, const Eigen::Vector3d& d) {
    return Eigen::Matrix3d(m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  const Eigen::Matrix3d expected =
      Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal().toDenseMatrix() + shift(2, ca - c) +
      Eigen::Vector3d(0.02, 0.01, 0.03).asDiagonal().toDenseMatrix() + shift(1, cb - c);
  EXPECT_TRUE(near_rel(model.body_inertia_c[0], expected, 1e-14));
  // frames keep their placement in their body
  const int fb = model.frame_id("b");
  EXPECT_EQ(model.frame_body[static_cast<std::size_t>(fb)], 0);
  EXPECT_TRUE(model.frame_p_BF[static_cast<std::size_t>(fb)].isApprox(Eigen::Vector3d(0, 0.5, 0)));
  const int fm = model.frame_id("marker");
  EXPECT_EQ(model.frame_body[static_cast<std::size_t>(fm)], 1);
  EXPECT_TRUE(model.frame_p_BF[static_cast<std::size_t>(fm)].isApprox(Eigen::Vector3d(0, 0, 0.2)));
  // limits kept
  EXPECT_EQ(model.joint_name[0], "b_to_c");
  EXPECT_DOUBLE_EQ(model.joint_lower[0], -1.5);
  EXPECT_DOUBLE_EQ(model.joint_upper[0], 2.0);
  EXPECT_DOUBLE_EQ(model.joint_effort_limit[0], 12.0);
  EXPECT_DOUBLE_EQ(model.joint_velocity_limit[0], 3.0);
}

TEST(Loader, MassAndComMatchDirectSumOverUrdfInertials) {
  std::vector<std::filesystem::path> models = wbi::test::project_models();
  for (const auto& p : wbi::test::shared_models()) {
    models.push_back(p);
  }
  for (const auto& path : models) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    wbi::test::Reference ref(path.string(), model.floating_base, model.joint_name);
    std::mt19937 rng(3);
    const Eigen::VectorXd q = wm::random_configuration(model, rng);
    ref.set_state(q, Eigen::VectorXd::Zero(model.nv));
    EXPECT_NEAR(model.total_mass, ref.total_mass(), 1e-12 * ref.total_mass());
    EXPECT_TRUE(near_rel(wm::center_of_mass(model, data, q), ref.com(), 1e-12));
  }
}

TEST(Loader, BaseKind) {
  // the root "world" is massless: fixed base
  const wm::Model pendulum = wm::load_urdf_file(wbi::test::project_model("pendulum.urdf").string());
  EXPECT_FALSE(pendulum.floating_base);
  // fixed base on request
  wm::LoadOptions fixed;
  fixed.fixed_base = true;
  const wm::Model lump = wm::load_urdf_string(kLumpUrdf, fixed);
  EXPECT_FALSE(lump.floating_base);
  EXPECT_EQ(lump.nq, 1);
  EXPECT_EQ(lump.nv, 1);
  // a root named world with mass stays free-floating
  const std::string heavy_world = replace(kLumpUrdf, "<link name=\"a\">", "<link name=\"world\">");
  const wm::Model w = wm::load_urdf_string(
      replace(heavy_world, "<parent link=\"a\"/>", "<parent link=\"world\"/>"));
  EXPECT_TRUE(w.floating_base);
  if (const auto dir = wbi::test::shared_models_dir()) {
    EXPECT_FALSE(wm::load_urdf_file((*dir / "ur5/ur5_robot.urdf").string()).floating_base);
    const wm::Model anymal = wm::load_urdf_file((*dir / "anymal_c/anymal.urdf").string());
    EXPECT_TRUE(
        anymal.floating_base);  // massless root "base": mass comes from the lumped base_inertia
    EXPECT_EQ(anymal.n_joints, 12);
    EXPECT_GT(anymal.body_mass[0], 0.0);
  }
}

TEST(Loader, ProjectModelsStructure) {
  const auto arm = wbi::test::project_model("arm7.urdf");
  if (std::filesystem::exists(arm)) {
    const wm::Model model = wm::load_urdf_file(arm.string());
    EXPECT_FALSE(model.floating_base);
    EXPECT_EQ(model.n_joints, 7);
    EXPECT_EQ(model.nv, 7);
  }
  const auto humanoid = wbi::test::project_model("humanoid.urdf");
  if (std::filesystem::exists(humanoid)) {
    const wm::Model model = wm::load_urdf_file(humanoid.string());
    EXPECT_TRUE(model.floating_base);
    EXPECT_EQ(model.n_joints, 30);
    EXPECT_EQ(model.nv, 36);
    EXPECT_EQ(model.nq, 37);
  }
}

TEST(Loader, SharedModelsLoadWithExpectedSizes) {
  const auto dir = wbi::test::shared_models_dir();
  if (!dir) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  struct Expected {
    const char* file;
    int dof;
    int links;
    bool floating;
  };
  for (const Expected& e :
       {Expected{"iCubGazeboV2_5/model.urdf", 32, 213, true},
        Expected{"iCubGenova09/model.urdf", 32, 58, true},
        Expected{"talos/talos_reduced.urdf", 32, 60, true},
        Expected{"talos/talos_full_v2.urdf", 44, 60, true},
        Expected{"atlas/atlas.urdf", 30, 31, true}, Expected{"anymal_c/anymal.urdf", 12, 78, true},
        Expected{"hyq/hyq_no_sensors.urdf", 12, 19, true}, Expected{"hyq/hyq.urdf", 12, 13, true},
        Expected{"solo12/solo12.urdf", 12, 17, true}, Expected{"panda/panda.urdf", 9, 13, true},
        Expected{"ur5/ur5_robot.urdf", 6, 11, false}, Expected{"iiwa/iiwa.urdf", 7, 9, true}}) {
    SCOPED_TRACE(e.file);
    const wm::Model model = wm::load_urdf_file((*dir / e.file).string());
    EXPECT_EQ(model.n_joints, e.dof);
    EXPECT_EQ(model.n_frames(), e.links);
    EXPECT_EQ(model.floating_base, e.floating);
  }
}

TEST(Loader, MimicJointsAreIndependentJoints) {
  const auto dir = wbi::test::shared_models_dir();
  if (!dir) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  const wm::Model panda = wm::load_urdf_file((*dir / "panda/panda.urdf").string());
  int mimics = 0;
  for (int k = 0; k < panda.n_joints; ++k) {
    const auto& m = panda.joint_mimic[static_cast<std::size_t>(k)];
    if (!m.joint.empty()) {
      ++mimics;
      EXPECT_TRUE(panda.has_joint(m.joint));
      EXPECT_EQ(panda.joint_type[static_cast<std::size_t>(k)], wm::JointType::kPrismatic);
    }
  }
  EXPECT_EQ(mimics, 1);
  const wm::Model talos = wm::load_urdf_file((*dir / "talos/talos_full_v2.urdf").string());
  mimics = 0;
  for (const auto& m : talos.joint_mimic) {
    mimics += m.joint.empty() ? 0 : 1;
  }
  EXPECT_EQ(mimics, 12);
}

TEST(Loader, ReducedModelAgreesWithFullModelAtLockedPositions) {
  std::vector<std::filesystem::path> paths;
  if (std::filesystem::exists(wbi::test::project_model("humanoid.urdf"))) {
    paths.push_back(wbi::test::project_model("humanoid.urdf"));
  }
  if (const auto dir = wbi::test::shared_models_dir()) {
    paths.push_back(*dir / "iCubGenova09/model.urdf");
  }
  for (const auto& path : paths) {
    SCOPED_TRACE(path.string());
    const wm::Model full = wm::load_urdf_file(path.string());
    std::mt19937 rng(4);
    const Eigen::VectorXd q_full = wm::random_configuration(full, rng);
    // keep every other joint, in reverse order; lock the rest at their values in q_full
    wm::LoadOptions options;
    for (int k = full.n_joints - 1; k >= 0; k -= 2) {
      options.joints.push_back(full.joint_name[static_cast<std::size_t>(k)]);
    }
    for (int k = 0; k < full.n_joints; ++k) {
      options.locked_positions[full.joint_name[static_cast<std::size_t>(k)]] =
          q_full[full.joint_q_index[static_cast<std::size_t>(k)]];
    }
    const wm::Model red = wm::load_urdf_file(path.string(), options);
    ASSERT_EQ(red.n_joints, static_cast<int>(options.joints.size()));
    EXPECT_EQ(red.joint_name, options.joints);  // order = list order
    EXPECT_EQ(static_cast<int>(red.locked_joint_name.size()), full.n_joints - red.n_joints);
    // indices of the kept velocities in the full model
    std::vector<int> idx{0, 1, 2, 3, 4, 5};
    Eigen::VectorXd q_red(red.nq);
    q_red.head<7>() = q_full.head<7>();
    for (int k = 0; k < red.n_joints; ++k) {
      const int kf = full.joint_id(red.joint_name[static_cast<std::size_t>(k)]);
      idx.push_back(full.joint_v_index[static_cast<std::size_t>(kf)]);
      q_red[red.joint_q_index[static_cast<std::size_t>(k)]] =
          q_full[full.joint_q_index[static_cast<std::size_t>(kf)]];
    }
    const int n = red.nv;
    Eigen::VectorXd nu_red = wbi::test::random_vector(n, rng, 1.0);
    Eigen::VectorXd nu_full = Eigen::VectorXd::Zero(full.nv);
    for (int i = 0; i < n; ++i) {
      nu_full[idx[static_cast<std::size_t>(i)]] = nu_red[i];
    }
    wm::Data df(full), dr(red);
    const Eigen::MatrixXd Mf = wm::mass_matrix(full, df, q_full);
    const Eigen::MatrixXd Mr = wm::mass_matrix(red, dr, q_red);
    const Eigen::VectorXd hf = wm::bias_forces(full, df, q_full, nu_full, kGravity);
    const Eigen::VectorXd hr = wm::bias_forces(red, dr, q_red, nu_red, kGravity);
    Eigen::MatrixXd Mf_sub(n, n);
    Eigen::VectorXd hf_sub(n);
    for (int i = 0; i < n; ++i) {
      hf_sub[i] = hf[idx[static_cast<std::size_t>(i)]];
      for (int j = 0; j < n; ++j) {
        Mf_sub(i, j) = Mf(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
      }
    }
    EXPECT_TRUE(near_rel(Mr, Mf_sub, 1e-10));
    EXPECT_TRUE(near_rel(hr, hf_sub, 1e-10));
    EXPECT_NEAR(red.total_mass, full.total_mass, 1e-12);
    EXPECT_TRUE(
        near_rel(wm::center_of_mass(red, dr, q_red), wm::center_of_mass(full, df, q_full), 1e-12));
    wm::forward_kinematics(full, df, q_full);
    wm::forward_kinematics(red, dr, q_red);
    for (int f = 0; f < full.n_frames(); ++f) {
      const std::string& name = full.frame_name[static_cast<std::size_t>(f)];
      EXPECT_TRUE(
          near_rel(wm::frame_pose(red, dr, red.frame_id(name)), wm::frame_pose(full, df, f), 1e-12))
          << name;
    }
  }
}

TEST(Loader, BadInputGivesClearErrors) {
  const std::string good = kLumpUrdf;
  // missing and empty files
  try {
    (void)wm::load_urdf_file("/nonexistent/robot.urdf");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/robot.urdf"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
  expect_load_error("empty.urdf", "  \n", {"empty"});
  expect_load_error("xml.urdf", replace(good, "</robot>", "</robt>"), {"XML error", "line"});
  expect_load_error("notrobot.urdf", "<?xml version=\"1.0\"?><model/>", {"<robot>"});
  // several roots, kinematic loop, dangling link
  expect_load_error(
      "roots.urdf",
      replace(good, "<link name=\"marker\"/>", "<link name=\"marker\"/><link name=\"island\"/>"),
      {"several root links", "island"});
  expect_load_error("loop.urdf",
                    replace(good, "</robot>",
                            "<joint name=\"back\" type=\"fixed\"><parent link=\"marker\"/><child "
                            "link=\"b\"/></joint></robot>"),
                    {"loop", "'b'"});
  expect_load_error("dangling.urdf",
                    replace(good, "<child link=\"marker\"/>", "<child link=\"nowhere\"/>"),
                    {"unknown link", "nowhere"});
  // zero axis, negative mass, non-physical inertia, unsupported joint type
  expect_load_error("axis.urdf", replace(good, "<axis xyz=\"1 0 0\"/>", "<axis xyz=\"0 0 0\"/>"),
                    {"zero axis", "b_to_c"});
  expect_load_error("mass.urdf", replace(good, "<mass value=\"0.5\"/>", "<mass value=\"-0.5\"/>"),
                    {"negative", "mass", "'c'"});
  expect_load_error("inertia.urdf", replace(good, "ixx=\"0.01\"", "ixx=\"-0.01\""),
                    {"non-physical inertia", "'b'"});
  wm::LoadOptions strict;
  strict.strict_inertia = true;
  expect_load_error("indefinite.urdf",
                    replace(good, "ixx=\"0.01\" ixy=\"0\"", "ixx=\"0.01\" ixy=\"0.5\""),
                    {"non-physical inertia", "'b'"}, strict);
  expect_load_error("triangle.urdf", replace(good, "izz=\"0.03\"", "izz=\"0.5\""),
                    {"non-physical inertia", "'b'"}, strict);
  expect_load_error("floating.urdf", replace(good, "type=\"revolute\"", "type=\"floating\""),
                    {"b_to_c", "not supported"});
  // unknown names in the options
  wm::LoadOptions unknown;
  unknown.joints = {"no_such_joint"};
  expect_load_error("unknown_joint.urdf", good, {"unknown joint", "no_such_joint"}, unknown);
  wm::LoadOptions fixed_listed;
  fixed_listed.joints = {"a_to_b"};
  expect_load_error("fixed_listed.urdf", good, {"a_to_b", "fixed"}, fixed_listed);
}

TEST(Loader, BadArgumentsGiveClearErrors) {
  const wm::Model model = wm::load_urdf_string(kLumpUrdf);
  wm::Data data(model);
  auto expect_error = [](const std::function<void()>& f, const std::vector<std::string>& words) {
    try {
      f();
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      for (const auto& w : words) {
        EXPECT_NE(std::string(e.what()).find(w), std::string::npos)
            << "'" << w << "' not in: " << e.what();
      }
    }
  };
  const Eigen::VectorXd q = wm::neutral_configuration(model);
  const Eigen::VectorXd nu = Eigen::VectorXd::Zero(model.nv);
  expect_error([&] { model.frame_id("nope"); }, {"unknown frame", "nope"});
  expect_error([&] { model.joint_id("nope"); }, {"unknown joint", "nope"});
  expect_error([&] { wm::mass_matrix(model, data, Eigen::VectorXd::Zero(3)); },
               {"'q'", "size 3", "expected 8"});
  expect_error([&] { wm::bias_forces(model, data, q, Eigen::VectorXd::Zero(2), kGravity); },
               {"'nu'", "expected 7"});
  expect_error(
      [&] { wm::inverse_dynamics(model, data, q, nu, Eigen::VectorXd::Zero(9), kGravity); },
      {"'dnu'", "expected 7"});
  expect_error(
      [&] { wm::forward_dynamics(model, data, q, nu, Eigen::VectorXd::Zero(1), kGravity); },
      {"'tau'", "expected 7"});
  expect_error([&] { wm::frame_jacobian(model, data, 99); }, {"frame index 99"});
  Eigen::VectorXd bad = q;
  bad.segment<4>(3).setZero();
  expect_error([&] { wm::forward_kinematics(model, data, bad); }, {"quaternion", "norm 0"});
  bad.segment<4>(3) << 1.0, 0.1, 0.0, 0.0;
  expect_error([&] { wm::mass_matrix(model, data, bad); }, {"quaternion", "unit"});
  bad = q;
  bad[0] = std::nan("");
  expect_error([&] { wm::gravity_forces(model, data, bad, kGravity); }, {"not finite"});
}

TEST(Loader, ConfigurationHelpers) {
  const wm::Model model = wm::load_urdf_string(kLumpUrdf);
  const Eigen::Quaterniond quat =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d p(0.1, -0.2, 0.3);
  Eigen::VectorXd s(1);
  s << 0.4;
  const Eigen::VectorXd q = wm::make_configuration(model, p, quat, s);
  EXPECT_EQ(q.size(), model.nq);
  EXPECT_DOUBLE_EQ(q[3], quat.w());  // order w, x, y, z
  EXPECT_DOUBLE_EQ(q[4], quat.x());
  EXPECT_DOUBLE_EQ(q[7], 0.4);
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H.topLeftCorner<3, 3>() = quat.toRotationMatrix();
  H.topRightCorner<3, 1>() = p;
  const Eigen::VectorXd q2 = wm::make_configuration(model, H, s);
  Eigen::VectorXd q_flipped = q;  // −quat is the same rotation
  q_flipped.segment<4>(3) *= -1.0;
  EXPECT_TRUE(q2.isApprox(q, 1e-14) || q2.isApprox(q_flipped, 1e-14));
  // the base frame lands where the transform says
  wm::Data data(model);
  wm::forward_kinematics(model, data, q2);
  EXPECT_TRUE(near_rel(wm::frame_pose(model, data, model.frame_id("a")), H, 1e-14));
  H(0, 0) = 2.0;
  EXPECT_THROW(wm::make_configuration(model, H, s), std::invalid_argument);
  // a fixed-base model takes only the identity pose
  wm::LoadOptions fixed;
  fixed.fixed_base = true;
  const wm::Model fixed_model = wm::load_urdf_string(kLumpUrdf, fixed);
  EXPECT_THROW(wm::make_configuration(fixed_model, p, quat, s), std::invalid_argument);
  EXPECT_EQ(wm::make_configuration(fixed_model, Eigen::Vector3d::Zero(),
                                   Eigen::Quaterniond::Identity(), s)
                .size(),
            1);
  // a Data of another model is refused
  wm::Data other(fixed_model);
  EXPECT_THROW(wm::mass_matrix(model, other, q), std::invalid_argument);
}

TEST(Loader, MasslessLeafOnAJointIsReportedByForwardDynamics) {
  const std::string massless =
      replace(kLumpUrdf, R"(<inertial><origin xyz="0 0 0.1" rpy="0 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>)",
              "");
  const wm::Model model = wm::load_urdf_string(massless);
  wm::Data data(model);
  const Eigen::VectorXd q = wm::neutral_configuration(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.nv);
  try {
    wm::forward_dynamics(model, data, q, zero, zero, kGravity);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("b_to_c"), std::string::npos) << e.what();
  }
}
