// Closed-form checks on the pendulum and the double pendulum (models/*.urdf,
// parameters in the file headers).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model_test_common.hpp"

namespace wm = wbi::model;
using wbi::test::project_model;

namespace {
const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);
constexpr double g = 9.81;
}  // namespace

TEST(ClosedForm, PendulumIsFixedBaseWithOneJoint) {
  const wm::Model model = wm::load_urdf_file(project_model("pendulum.urdf").string());
  EXPECT_FALSE(model.floating_base);  // root is a massless link named "world"
  EXPECT_EQ(model.nq, 1);
  EXPECT_EQ(model.nv, 1);
  EXPECT_EQ(model.n_bodies, 2);
  EXPECT_EQ(model.n_frames(), 3);  // world, rod, tip
  EXPECT_DOUBLE_EQ(model.total_mass, 2.0);
}

TEST(ClosedForm, PendulumDynamics) {
  const wm::Model model = wm::load_urdf_file(project_model("pendulum.urdf").string());
  wm::Data data(model);
  const double m = 2.0, lc = 0.5, Iyy = 0.1;
  for (double q0 : {0.0, 0.3, -1.2, 2.5}) {
    Eigen::VectorXd q(1), v(1), a(1), tau(1);
    q << q0;
    v << 1.7;
    a << -0.4;
    EXPECT_NEAR(wm::mass_matrix(model, data, q)(0, 0), Iyy + m * lc * lc, 1e-12);
    EXPECT_NEAR(wm::gravity_forces(model, data, q, kGravity)[0], m * g * lc * std::sin(q0), 1e-12);
    // no Coriolis term for one joint: h = G
    EXPECT_NEAR(wm::bias_forces(model, data, q, v, kGravity)[0], m * g * lc * std::sin(q0), 1e-12);
    const double tau_expected = (Iyy + m * lc * lc) * a[0] + m * g * lc * std::sin(q0);
    EXPECT_NEAR(wm::inverse_dynamics(model, data, q, v, a, kGravity)[0], tau_expected, 1e-12);
    tau << 0.0;
    EXPECT_NEAR(wm::forward_dynamics(model, data, q, v, tau, kGravity)[0],
                -m * g * lc * std::sin(q0) / (Iyy + m * lc * lc), 1e-12);
    // tip 1 m below the hinge, rotated about y: (−sin q, 0, −cos q)
    wm::forward_kinematics(model, data, q);
    const Eigen::Matrix4d H = wm::frame_pose(model, data, model.frame_id("tip"));
    EXPECT_NEAR(H(0, 3), -std::sin(q0), 1e-12);
    EXPECT_NEAR(H(2, 3), -std::cos(q0), 1e-12);
    // Jacobian of the tip: ṗ = (−cos q, 0, sin q) q̇, ω = (0, 1, 0) q̇
    const Eigen::MatrixXd& J = wm::frame_jacobian(model, data, model.frame_id("tip"));
    Eigen::Matrix<double, 6, 1> expected;
    expected << -std::cos(q0), 0, std::sin(q0), 0, 1, 0;
    EXPECT_TRUE(J.col(0).isApprox(expected, 1e-12)) << J;
    // CoM 0.5 m below the hinge
    const Eigen::Vector3d c = wm::center_of_mass(model, data, q);
    EXPECT_NEAR(c.x(), -lc * std::sin(q0), 1e-12);
    EXPECT_NEAR(c.z(), -lc * std::cos(q0), 1e-12);
  }
}

TEST(ClosedForm, DoublePendulumDynamics) {
  const wm::Model model = wm::load_urdf_file(project_model("double_pendulum.urdf").string());
  ASSERT_EQ(model.nv, 2);
  ASSERT_EQ(model.joint_name[0], "joint1");
  ASSERT_EQ(model.joint_name[1], "joint2");
  EXPECT_TRUE(model.joint_continuous[1]);
  wm::Data data(model);
  const double m1 = 1.5, c1 = 0.4, I1 = 0.05, l1 = 0.8, m2 = 1.0, c2 = 0.3, I2 = 0.03;
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = wbi::test::random_vector(2, rng, 3.0);
    const Eigen::VectorXd v = wbi::test::random_vector(2, rng, 2.0);
    const Eigen::VectorXd a = wbi::test::random_vector(2, rng, 2.0);
    const double t1 = q[0], t2 = q[1], d1 = v[0], d2 = v[1];
    Eigen::Matrix2d M;
    M(0, 0) = I1 + I2 + m1 * c1 * c1 + m2 * (l1 * l1 + c2 * c2 + 2 * l1 * c2 * std::cos(t2));
    M(0, 1) = M(1, 0) = I2 + m2 * (c2 * c2 + l1 * c2 * std::cos(t2));
    M(1, 1) = I2 + m2 * c2 * c2;
    Eigen::Vector2d G((m1 * c1 + m2 * l1) * g * std::sin(t1) + m2 * c2 * g * std::sin(t1 + t2),
                      m2 * c2 * g * std::sin(t1 + t2));
    Eigen::Vector2d C(-m2 * l1 * c2 * std::sin(t2) * (2 * d1 * d2 + d2 * d2),
                      m2 * l1 * c2 * std::sin(t2) * d1 * d1);
    EXPECT_TRUE(wbi::test::near_rel(wm::mass_matrix(model, data, q), M, 1e-12));
    EXPECT_TRUE(wbi::test::near_rel(wm::gravity_forces(model, data, q, kGravity), G, 1e-12));
    EXPECT_TRUE(wbi::test::near_rel(wm::bias_forces(model, data, q, v, kGravity), C + G, 1e-12));
    EXPECT_TRUE(wbi::test::near_rel(wm::inverse_dynamics(model, data, q, v, a, kGravity),
                                    M * a + C + G, 1e-12));
    const Eigen::Vector2d tau = wbi::test::random_vector(2, rng, 5.0);
    EXPECT_TRUE(wbi::test::near_rel(wm::forward_dynamics(model, data, q, v, tau, kGravity),
                                    M.inverse() * (tau - C - G), 1e-10));
  }
}

TEST(ClosedForm, GravityIsAnInput) {
  const wm::Model model = wm::load_urdf_file(project_model("pendulum.urdf").string());
  wm::Data data(model);
  Eigen::VectorXd q(1);
  q << 0.0;
  // V = −m g·c = −2·3·(−0.5 sin q) = 3 sin q, so G = 3 cos q = 3 at q = 0
  EXPECT_NEAR(wm::gravity_forces(model, data, q, Eigen::Vector3d(3.0, 0.0, 0.0))[0], 3.0, 1e-12);
  EXPECT_NEAR(wm::gravity_forces(model, data, q, Eigen::Vector3d::Zero())[0], 0.0, 1e-15);
}
