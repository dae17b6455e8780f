// The proxy's local model computing with DART: the paper's PD + gravity
// controller, unchanged, sends τ = G_j(q) − K_p (q − q_d) − K_d q̇ with G from
// the model library to 1e-9, and the interface's model queries agree with the
// "wbi" local model. Only DdsInterfaceOptions::local_model_backend differs.
#include <gtest/gtest.h>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/model/algorithms.hpp>

#include "arm_peer.hpp"
#include "backend_test_common.hpp"

namespace {

using namespace wbi::test;

TEST(ProxyBackend, PdGravityWithTheDartLocalModel) {
  if (!dart_built()) {
    GTEST_SKIP() << kDartMissing;
  }
  ArmPeer peer("arm_dart");
  auto options = arm_options("arm_dart");
  options.local_model_backend = "dart";
  auto robot = wbi::make_dds_interface(options);
  robot->add_joints(kArmJoints);
  robot->init(10s);

  const int n = robot->dofs();
  wbi::controllers::PdGravityGains gains{Eigen::VectorXd::Constant(n, 50.0),
                                         Eigen::VectorXd::Constant(n, 5.0)};
  const Eigen::VectorXd q_desired = Eigen::VectorXd::LinSpaced(n, 0.2, -0.2);
  wbi::controllers::PdGravity controller(*robot, gains, q_desired);
  controller.start();
  controller.update(wbi::ReadMode::blocking);

  wbi::dds::Received<wbi::msg::ActuatorCommand> command;
  ASSERT_TRUE(peer.commands().wait_newer(command, 1, 5s));  // mode first, then torques
  const auto full = wbi::model::load_urdf_file(project_model("arm7.urdf").string());
  wbi::model::Data data(full);
  Eigen::VectorXd q(n), dq(n);
  for (int j = 0; j < n; ++j) {
    q[j] = arm_position(static_cast<std::size_t>(j));
    dq[j] = arm_velocity(static_cast<std::size_t>(j));
  }
  const Eigen::VectorXd g = wbi::model::gravity_forces(full, data, q, Eigen::Vector3d(0, 0, -9.81));
  const Eigen::VectorXd expected =
      g - gains.kp.cwiseProduct(q - q_desired) - gains.kd.cwiseProduct(dq);
  ASSERT_EQ(command.sample.references().size(), static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
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
