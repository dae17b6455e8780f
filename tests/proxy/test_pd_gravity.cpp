// The PD + gravity controller, through the DDS whole-body interface, sends
// τ = G_j(q) − K_p (q − q_d) − K_d q̇ computed at the robot's estimated state.
#include <gtest/gtest.h>

#include "pd_gravity_on_arm.hpp"

namespace {

using namespace wbi::test;

TEST(PdGravity, SendsThePaperTorques) {
  ArmPeer peer("arm_pd");
  PdGravityOnArm pd(arm_options("arm_pd"));
  wbi::dds::Received<wbi::msg::ActuatorCommand> command;
  ASSERT_TRUE(pd.update_and_receive(peer, command));

  const Eigen::VectorXd expected = pd.expected_torques();
  ASSERT_EQ(command.sample.references().size(), static_cast<std::size_t>(pd.n));
  for (int j = 0; j < pd.n; ++j) {
    EXPECT_EQ(command.sample.modes()[static_cast<std::size_t>(j)], wbi::msg::ControlMode::TORQUE);
    EXPECT_NEAR(command.sample.references()[static_cast<std::size_t>(j)], expected[j], 1e-9) << j;
  }
  EXPECT_NEAR(pd.controller.max_error(), (pd.peer_q() - pd.q_desired).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(pd.controller.set_reference(Eigen::VectorXd::Zero(pd.n + 1)), wbi::Error);
}

// A live gain_scale multiplies the PD terms; bound to some of a host's joints,
// the others' errors and velocities couple in nothing (their columns of the
// coupled gains do not count), while max_error still reads every joint.
TEST(PdGravity, ScalesItsGainsAndCountsOnlyItsOwnJoints) {
  ArmPeer peer("arm_pd_own");
  PdGravityOnArm pd(arm_options("arm_pd_own"));
  const int n = pd.n;
  Eigen::MatrixXd kp = Eigen::MatrixXd::Constant(n, n, 3.0);  // coupled: every column counts
  kp.diagonal().setConstant(40.0);
  const Eigen::MatrixXd kd = 0.1 * kp;
  pd.controller.set_gains(kp, kd);
  pd.controller.set_gain_scale(0.5);
  const int own[] = {0, 2};
  pd.controller.set_own_joints(own);
  wbi::dds::Received<wbi::msg::ActuatorCommand> command;
  ASSERT_TRUE(pd.update_and_receive(peer, command));

  Eigen::VectorXd mask = Eigen::VectorXd::Zero(n);
  mask[0] = mask[2] = 1.0;
  pd.gains = {kp, kd};
  const Eigen::VectorXd unscaled = pd.expected_torques();
  pd.gains = {Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  const Eigen::VectorXd gravity = pd.expected_torques();
  const Eigen::VectorXd error = (pd.peer_q() - pd.q_desired).cwiseProduct(mask);
  const Eigen::VectorXd expected =
      gravity - 0.5 * (kp * error + kd * pd.peer_dq().cwiseProduct(mask));
  ASSERT_GT((expected - unscaled).cwiseAbs().maxCoeff(), 1e-3);  // the scale and mask tell
  for (int j = 0; j < n; ++j) {
    EXPECT_NEAR(command.sample.references()[static_cast<std::size_t>(j)], expected[j], 1e-9) << j;
  }
  EXPECT_NEAR(pd.controller.max_error(), (pd.peer_q() - pd.q_desired).cwiseAbs().maxCoeff(), 1e-12);
  const int outside[] = {n};
  EXPECT_THROW(pd.controller.set_own_joints(outside), wbi::Error);
}

}  // namespace
