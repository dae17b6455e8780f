// The paper's example, whole: PD + gravity compensation written against the
// whole-body interface only. τ = G_j(q) − K_p (q − q_d) − K_d q̇ at the rate of
// the state estimates, for `ticks` estimates; K_p = ω² m_j, K_d = 2ω m_j. Usage:
//   wbi_example_pd_gravity URDF [TICKS]       (robot "arm", e.g. deploy/demo.yaml's)
#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <string>

#include <wbi/dds_interface.hpp>

int main(int argc, char** argv) {
  if (argc < 2) return std::fprintf(stderr, "usage: %s URDF [TICKS]\n", argv[0]), 2;
  auto robot = wbi::make_dds_interface({.robot = "arm", .urdf = argv[1]});  // model: here
  robot->add_joints({"joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6", "joint_7"});
  robot->init();
  const int n = robot->dofs(), ticks = argc > 2 ? std::stoi(argv[2]) : 5000;
  Eigen::VectorXd g(6 + n), tau(n), q_d{{0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0}};  // q_d: target
  Eigen::MatrixXd M(6 + n, 6 + n);
  robot->mass_matrix(q_d, wbi::Transform::Identity(), M);  // each joint's inertia, others free:
  const Eigen::VectorXd m = M.bottomRightCorner(n, n).inverse().diagonal().cwiseInverse();
  const double w = 2 * M_PI * 5.0;  // each joint critically damped at 5 Hz
  const Eigen::VectorXd kp = w * w * m, kd = 2 * w * m;
  robot->set_control_mode(wbi::ControlMode::torque);
  wbi::RobotState s(n);  // q, dq, ddq, base pose and velocity of one estimate
  for (int tick = 0; tick < ticks; ++tick) {
    robot->read_robot_state(s, wbi::ReadMode::blocking);  // one call, one estimate
    robot->gravity_forces(s.q, s.world_H_base, Eigen::Vector3d(0, 0, -9.81), g);
    tau = g.tail(n) - kp.cwiseProduct(s.q - q_d) - kd.cwiseProduct(s.dq);
    robot->set_control_reference(tau);
  }
  std::printf("final max joint error: %.6f rad\n", (s.q - q_d).cwiseAbs().maxCoeff());
}
