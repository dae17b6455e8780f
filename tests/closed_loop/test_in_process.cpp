// The whole chain in one process, over real DDS: the simulated arm (lockstep),
// the estimator, and the PD + gravity controller through the DDS whole-body
// interface. The arm moves to the target posture; two lockstep runs produce
// the same trajectory bit for bit.
#include <gtest/gtest.h>

#include <chrono>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

const std::vector<std::string> kArm{"joint_1", "joint_2", "joint_3", "joint_4",
                                    "joint_5", "joint_6", "joint_7"};

struct ArmRun {
  double final_error = 0.0;
  std::vector<double> torques;  // the controller's torques, tick after tick
};

// One lockstep run of `ticks` control ticks on robot `robot`.
ArmRun run_arm(const std::string& robot, int ticks) {
  const auto config = (wbi::test::source_dir() / "deploy" / "robots" / "arm.yaml").string();
  // Backward difference with a 100 Hz low-pass: the kalman method's extrapolation
  // drives this stiff loop unstable (see estimation/README.md).
  wbi::sim_rig::InProcessRobot rig(
      "closed_loop",
      "robot: " + robot + "\nconfig: " + config + "\nlockstep: true\nlockstep_controllers: [pd]\n",
      "robot: " + robot + "\nmethod: backward-difference\ncutoff: 100\n");

  wbi::DdsInterfaceOptions options;
  options.robot = robot;
  options.controller = "pd";
  options.urdf = wbi::test::project_model("arm7.urdf").string();
  options.max_age_s = 5.0;  // lockstep: time is the simulation's
  auto arm = wbi::make_dds_interface(options);
  arm->add_joints(kArm);
  rig.start_simulation();
  arm->init(20s);

  const int n = arm->dofs();
  Eigen::VectorXd q_desired(n);
  q_desired << 0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0;
  // Gains from the joints' inertia at the target (mass-matrix diagonal): a
  // critically damped 6 Hz response for every joint, so the light wrist is not
  // driven unstable by the one-tick delay of the loop.
  Eigen::MatrixXd M(6 + n, 6 + n);
  arm->mass_matrix(q_desired, wbi::Transform::Identity(), M);
  const auto gains = wbi::controllers::PdGravityGains::from_inertia(M.bottomRightCorner(n, n), 6.0);
  wbi::controllers::PdGravity pd(*arm, gains, q_desired);
  pd.start();
  ArmRun run;
  for (int k = 0; k < ticks; ++k) {
    pd.update(wbi::ReadMode::blocking);
    run.torques.insert(run.torques.end(), pd.torques().begin(), pd.torques().end());
  }
  run.final_error = pd.max_error();
  rig.sim().shutdown();
  rig.estimator().shutdown();
  return run;
}

TEST(ClosedLoopInProcess, PdGravityReachesTheTargetDeterministically) {
  const ArmRun first = run_arm("arm_loop_a", 3000);
  EXPECT_LT(first.final_error, 0.01) << "rad after 3 s";
  const ArmRun second = run_arm("arm_loop_b", 3000);
  EXPECT_EQ(first.final_error, second.final_error);
  ASSERT_EQ(first.torques.size(), 7u * 3000u);
  EXPECT_TRUE(first.torques == second.torques) << "lockstep runs differ";
}

}  // namespace
