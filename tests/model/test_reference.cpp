// Agreement with the independent naive implementation (reference.hpp) to 1e-9
// relative, on the project's models and on every model of ../shared/models:
// M, h, G, total mass, CoM, centroidal momentum matrix and momentum, and the
// pose, Jacobian and J̇ν of every frame (every URDF link).
#include <gtest/gtest.h>

#include <fstream>

#include "model_test_common.hpp"
#include "reference.hpp"

namespace wm = wbi::model;
using wbi::test::near_rel;

namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);
constexpr double kTol = 1e-9;

void compare_with_reference(const std::filesystem::path& path, bool fixed_base) {
  SCOPED_TRACE(path.string() + (fixed_base ? " (fixed base)" : ""));
  wm::LoadOptions options;
  options.fixed_base = fixed_base;
  const wm::Model model = wm::load_urdf_file(path.string(), options);
  wm::Data data(model);
  wbi::test::Reference ref(path.string(), model.floating_base, model.joint_name);
  ASSERT_EQ(ref.nv(), model.nv);
  EXPECT_NEAR(model.total_mass, ref.total_mass(), kTol * std::max(1.0, ref.total_mass()));
  std::mt19937 rng(42);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = wm::random_configuration(model, rng);
    const Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 2.0);
    ref.set_state(q, nu);
    EXPECT_TRUE(near_rel(wm::mass_matrix(model, data, q), ref.mass_matrix(), kTol)) << "M";
    EXPECT_TRUE(
        near_rel(wm::bias_forces(model, data, q, nu, kGravity), ref.bias_forces(kGravity), kTol))
        << "h";
    EXPECT_TRUE(
        near_rel(wm::gravity_forces(model, data, q, kGravity), ref.gravity_forces(kGravity), kTol))
        << "G";
    if (model.total_mass > 0.0) {
      EXPECT_TRUE(near_rel(wm::center_of_mass(model, data, q), ref.com(), kTol)) << "com";
      EXPECT_TRUE(near_rel(wm::centroidal_momentum_matrix(model, data, q),
                           ref.centroidal_momentum_matrix(), kTol))
          << "A_G";
      EXPECT_TRUE(
          near_rel(wm::centroidal_momentum(model, data, q, nu), ref.centroidal_momentum(), kTol))
          << "h_G";
    }
    wm::forward_velocity_kinematics(model, data, q, nu);
    ASSERT_EQ(model.n_frames() > 0, true);
    for (int f = 0; f < model.n_frames(); ++f) {
      const std::string& name = model.frame_name[static_cast<std::size_t>(f)];
      ASSERT_TRUE(ref.has_link(name)) << name;
      EXPECT_TRUE(near_rel(wm::frame_pose(model, data, f), ref.link_pose(name), kTol))
          << "pose " << name;
      EXPECT_TRUE(near_rel(wm::frame_jacobian(model, data, f), ref.link_jacobian(name), kTol))
          << "J " << name;
      EXPECT_TRUE(near_rel(wm::frame_bias_acceleration(model, data, f), ref.link_dJnu(name), kTol))
          << "dJnu " << name;
    }
    // the Jacobian from q (kinematics of the support only), into a fresh Data
    wm::Data fresh(model);
    for (int f = 0; f < model.n_frames(); f += 3) {
      const std::string& name = model.frame_name[static_cast<std::size_t>(f)];
      EXPECT_TRUE(near_rel(wm::frame_jacobian(model, fresh, q, f), ref.link_jacobian(name), kTol))
          << "J(q) " << name;
    }
  }
}

}  // namespace

TEST(Reference, SyntheticChainWithGeneralAxes) {
  // revolute and prismatic joints about general, negative and coordinate axes,
  // rotated joint origins, a branch, a massless intermediate link
  const char* urdf = R"(<?xml version="1.0"?>
<robot name="synthetic">
  <link name="base"><inertial><origin xyz="0.01 0.02 -0.03" rpy="0.1 0.2 0.3"/><mass value="3"/>
    <inertia ixx="0.05" ixy="0.001" ixz="-0.002" iyy="0.06" iyz="0.003" izz="0.07"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0.1 0 0.2" rpy="0.3 -0.2 0.1"/><axis xyz="1 2 3"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <link name="l1"><inertial><origin xyz="0 0.1 0" rpy="0 0 0.5"/><mass value="1.2"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.015"/></inertial></link>
  <joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0.2 0" rpy="0 0.4 0"/><axis xyz="0.3 -0.5 0.8"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <link name="l2"/>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.05 0 0.1" rpy="-0.5 0 0.2"/><axis xyz="0 0 -1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <link name="l3"><inertial><origin xyz="0.1 0 0" rpy="0 0 0"/><mass value="0.8"/>
    <inertia ixx="0.004" ixy="0.0005" ixz="0" iyy="0.006" iyz="0" izz="0.005"/></inertial></link>
  <joint name="j4" type="prismatic"><parent link="base"/><child link="l4"/>
    <origin xyz="-0.1 0 0" rpy="0 0 1.2"/><axis xyz="-1 0 0"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <link name="l4"><inertial><origin xyz="0 0 0.05" rpy="0 0 0"/><mass value="0.5"/>
    <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.001"/></inertial></link>
  <joint name="j5" type="continuous"><parent link="l4"/><child link="l5"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 -1 0"/></joint>
  <link name="l5"><inertial><origin xyz="0 0 0.05" rpy="0 0 0"/><mass value="0.3"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
</robot>)";
  const auto path = std::filesystem::temp_directory_path() / "wbi_model_test_synthetic.urdf";
  std::ofstream(path) << urdf;
  compare_with_reference(path, false);
  compare_with_reference(path, true);
}

TEST(Reference, ProjectModels) {
  for (const auto& path : wbi::test::project_models()) {
    compare_with_reference(path, false);
  }
}

TEST(Reference, SharedModelsDefaultBase) {
  if (!wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  for (const auto& path : wbi::test::shared_models()) {
    compare_with_reference(path, false);
  }
}

TEST(Reference, SharedModelsFixedBase) {
  if (!wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  for (const auto& path : wbi::test::shared_models()) {
    compare_with_reference(path, true);
  }
}
