// The remote model: the proxy's Model element answered by the model service
// in a wbi_host process. It agrees with the local model over the same joint
// subset (other joints locked where the robot measures them), maps the
// service's errors and a vanished service to errors naming the service and
// the operation, and init() names a missing service.
#include <gtest/gtest.h>

#include "remote_model_peer.hpp"

namespace {

using namespace wbi::test;

TEST(RemoteModel, AgreesWithTheLocalModelOverAJointSubset) {
  ArmPeer peer("arm_remote");
  const auto service = start_model_service("arm_remote");
  const wbi::IdList joints{"joint_4", "joint_2", "joint_6"};
  auto local = connect(arm_options("arm_remote"), joints);
  auto remote = connect(remote_options("arm_remote"), joints);
  const int n = 3;
  ASSERT_EQ(remote->dofs(), n);

  const Eigen::Vector3d q(0.3, -0.4, 0.7), dq(0.5, -1.0, 2.0), ddq(1.0, 2.0, -3.0);
  const wbi::Transform world_H_base = wbi::Transform::Identity();
  const Eigen::Matrix<double, 6, 1> base_velocity = Eigen::Matrix<double, 6, 1>::Zero();
  const Eigen::Vector3d gravity(0, 0, -9.81);
  const double tol = 1e-9;
  const auto both = [&](auto&& f) {
    auto a = f(*local);
    auto b = f(*remote);
    EXPECT_TRUE(a.isApprox(b, tol) || (a - b).norm() < tol) << "local\n" << a << "\nremote\n" << b;
    return b;
  };
  const auto g = both([&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd out(6 + n);
    r.gravity_forces(q, world_H_base, gravity, out);
    return out;
  });
  EXPECT_TRUE(g.head<6>().isZero());  // fixed base: base rows are zero
  EXPECT_FALSE(g.tail(n).isZero());
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::MatrixXd M(6 + n, 6 + n);
    r.mass_matrix(q, world_H_base, M);
    return M;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd h(6 + n);
    r.bias_forces(q, world_H_base, dq, base_velocity, gravity, h);
    return h;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd tau(6 + n);
    r.inverse_dynamics(q, world_H_base, dq, base_velocity, ddq, base_velocity, gravity, tau);
    return tau;
  });
  const int ee = remote->frame_index("ee_link");
  EXPECT_EQ(ee, local->frame_index("ee_link"));
  both([&](wbi::WholeBodyInterface& r) {
    wbi::Transform pose;
    r.frame_pose(q, world_H_base, ee, pose);
    return pose;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::MatrixXd J(6, 6 + n);
    r.jacobian(q, world_H_base, ee, J);
    return J;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd a(6);
    r.dj_nu(q, world_H_base, dq, base_velocity, ee, a);
    return a;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::Vector3d c;
    r.com(q, world_H_base, c);
    return c;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::MatrixXd J(3, 6 + n);
    r.com_jacobian(q, world_H_base, J);
    return J;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd h(6);
    r.centroidal_momentum(q, world_H_base, dq, base_velocity, h);
    return h;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::MatrixXd A(6, 6 + n);
    r.centroidal_momentum_matrix(q, world_H_base, A);
    return A;
  });
  EXPECT_EQ(remote->joint_limits(1).position_max, local->joint_limits(1).position_max);
  EXPECT_THROW(remote->frame_index("no_such_frame"), wbi::Error);
  Eigen::VectorXd wrong(4);
  EXPECT_THROW(remote->gravity_forces(wrong, world_H_base, gravity, wrong), wbi::Error);
}

TEST(RemoteModel, ErrorsNameTheServiceAndTheOperation) {
  ArmPeer peer("arm_remote_err");
  // No model service yet: init names it.
  auto options = remote_options("arm_remote_err");
  options.urdf = "/nonexistent.urdf";  // no frame names here: the service checks them
  {
    auto robot = wbi::make_dds_interface(options);
    robot->add_joints({"joint_1"});
    try {
      robot->init(1s);
      FAIL() << "init succeeded without a model service";
    } catch (const wbi::TimeoutError& e) {
      EXPECT_NE(std::string(e.what()).find("model service wbi/arm_remote_err/model"),
                std::string::npos)
          << e.what();
    }
  }
  auto service = start_model_service("arm_remote_err");
  auto robot = connect(options, {"joint_1", "joint_2"});
  Eigen::MatrixXd J(6, 8);
  const int bad = robot->frame_index("no_such_frame");
  try {
    robot->jacobian(Eigen::Vector2d::Zero(), wbi::Transform::Identity(), bad, J);
    FAIL() << "unknown frame accepted";
  } catch (const wbi::Error& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("remote model jacobian"), std::string::npos) << text;
    EXPECT_NE(text.find("wbi/arm_remote_err/model"), std::string::npos) << text;
    EXPECT_NE(text.find("no_such_frame"), std::string::npos) << text;
  }
  // The service goes away: a call fails within its deadline, naming both.
  service->stop();
  Eigen::VectorXd g(8);
  const auto start = std::chrono::steady_clock::now();
  try {
    robot->gravity_forces(Eigen::Vector2d::Zero(), wbi::Transform::Identity(),
                          Eigen::Vector3d(0, 0, -9.81), g);
    FAIL() << "a call succeeded without a model service";
  } catch (const wbi::TimeoutError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("remote model gravity_forces"), std::string::npos) << text;
    EXPECT_NE(text.find("wbi/arm_remote_err/model"), std::string::npos) << text;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, options.model_timeout + 1s);
}

}  // namespace
