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

}  // namespace
