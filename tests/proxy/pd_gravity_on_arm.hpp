// The paper's PD + gravity controller on the arm peer (arm_peer.hpp), through a
// DDS whole-body interface built from the given options: one update, the
// torques it sent and the torques the paper's law gives at the peer's state.
// Shared by the proxy's test and the DART local-model test, which differ only
// in DdsInterfaceOptions.
#pragma once

#include <chrono>
#include <memory>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/model/algorithms.hpp>

#include "arm_peer.hpp"

namespace wbi::test {

struct PdGravityOnArm {
  explicit PdGravityOnArm(const wbi::DdsInterfaceOptions& options)
      : robot(init(options)),
        n(robot->dofs()),
        gains(wbi::controllers::PdGravityGains::diagonal(Eigen::VectorXd::Constant(n, 50.0),
                                                         Eigen::VectorXd::Constant(n, 5.0))),
        q_desired(Eigen::VectorXd::LinSpaced(n, 0.2, -0.2)),
        controller(*robot, gains, q_desired) {}

  // Starts the controller (torque mode), runs one blocking update and waits for
  // the torques it sent (the peer's second command: the mode came first).
  bool update_and_receive(ArmPeer& peer, wbi::dds::Received<wbi::msg::ActuatorCommand>& command) {
    using namespace std::chrono_literals;
    controller.start();
    controller.update(wbi::ReadMode::blocking);
    return peer.commands().wait_newer(command, 1, 5s);
  }

  // τ = G_j(q) − K_p (q − q_d) − K_d q̇ at the peer's state, with the model library.
  Eigen::VectorXd expected_torques() const {
    const auto full = wbi::model::load_urdf_file(project_model("arm7.urdf").string());
    wbi::model::Data data(full);
    const Eigen::VectorXd g =
        wbi::model::gravity_forces(full, data, peer_q(), Eigen::Vector3d(0, 0, -9.81));
    return g - gains.kp * (peer_q() - q_desired) - gains.kd * peer_dq();
  }

  Eigen::VectorXd peer_q() const {
    Eigen::VectorXd q(n);
    for (int j = 0; j < n; ++j) {
      q[j] = arm_position(static_cast<std::size_t>(j));
    }
    return q;
  }
  Eigen::VectorXd peer_dq() const {
    Eigen::VectorXd dq(n);
    for (int j = 0; j < n; ++j) {
      dq[j] = arm_velocity(static_cast<std::size_t>(j));
    }
    return dq;
  }

  std::unique_ptr<wbi::WholeBodyInterface> robot;
  int n;
  wbi::controllers::PdGravityGains gains;
  Eigen::VectorXd q_desired;
  wbi::controllers::PdGravity controller;

 private:
  static std::unique_ptr<wbi::WholeBodyInterface> init(const wbi::DdsInterfaceOptions& options) {
    using namespace std::chrono_literals;
    auto robot = wbi::make_dds_interface(options);
    robot->add_joints(kArmJoints);
    robot->init(10s);
    return robot;
  }
};

}  // namespace wbi::test
