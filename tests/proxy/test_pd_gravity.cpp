// The PD + gravity controller, through the DDS whole-body interface, sends
// τ = G_j(q) − K_p (q − q_d) − K_d q̇ computed at the robot's estimated state.
#include <gtest/gtest.h>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/model/algorithms.hpp>

#include "arm_peer.hpp"

namespace {

using namespace wbi::test;

TEST(PdGravity, SendsThePaperTorques) {
  ArmPeer peer("arm_pd");
  auto robot = wbi::make_dds_interface(arm_options("arm_pd"));
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
  ASSERT_TRUE(peer.commands().wait_newer(command, 1, 5s));  // the 2nd command: mode, then torques
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
    EXPECT_EQ(command.sample.modes()[static_cast<std::size_t>(j)], wbi::msg::ControlMode::TORQUE);
    EXPECT_NEAR(command.sample.references()[static_cast<std::size_t>(j)], expected[j], 1e-9) << j;
  }
  EXPECT_NEAR(controller.max_error(), (q - q_desired).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(controller.set_reference(Eigen::VectorXd::Zero(n + 1)), wbi::Error);
}

}  // namespace
