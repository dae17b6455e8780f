// The proxy's local model computing with DART: the paper's PD + gravity
// controller, unchanged, sends τ = G_j(q) − K_p (q − q_d) − K_d q̇ with G from
// the model library to 1e-9, and the interface's model queries agree with the
// "wbi" local model. Only DdsInterfaceOptions::local_model_backend differs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "backend_test_common.hpp"
#include "pd_gravity_on_arm.hpp"

namespace {

using namespace wbi::test;

TEST(ProxyBackend, PdGravityWithTheDartLocalModel) {
  if (!dart_built()) {
    GTEST_SKIP() << kDartMissing;
  }
  ArmPeer peer("arm_dart");
  auto options = arm_options("arm_dart");
  options.local_model_backend = "dart";
  PdGravityOnArm pd(options);
  wbi::dds::Received<wbi::msg::ActuatorCommand> command;
  ASSERT_TRUE(pd.update_and_receive(peer, command));

  const Eigen::VectorXd expected = pd.expected_torques();
  ASSERT_EQ(command.sample.references().size(), static_cast<std::size_t>(pd.n));
  for (int j = 0; j < pd.n; ++j) {
    EXPECT_NEAR(command.sample.references()[static_cast<std::size_t>(j)], expected[j],
                1e-9 * std::max(1.0, std::abs(expected[j])))
        << j;
  }
}

TEST(ProxyBackend, UnknownLocalModelBackendIsNamed) {
  ArmPeer peer("arm_bad_backend");
  auto options = arm_options("arm_bad_backend");
  options.local_model_backend = "pinocchio";
  try {
    auto robot = wbi::make_dds_interface(options);
    robot->add_joints(kArmJoints);
    robot->init(10s);
    FAIL() << "no error";
  } catch (const wbi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown model backend 'pinocchio'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
