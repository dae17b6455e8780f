// The sim_robot component with `engine: mujoco`, over DDS in one process
// (sim_rig::InProcessRobot: the robot loop in lockstep and the estimator), and
// the PD + gravity controller through the DDS whole-body interface: the arm on
// MuJoCo reaches its target, and two lockstep runs are identical to the bit.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

#ifndef WBI_WITH_MUJOCO
TEST(MujocoSimRobot, SkippedWithoutMujoco) {
  GTEST_SKIP() << "this build has no MuJoCo (install libmujoco-dev: scripts/install-deps)";
}
#else

struct ArmRun {
  double final_error = 0.0;
  std::vector<double> torques;  // the controller's torques, tick after tick
};

ArmRun run_arm(const std::string& robot, int ticks) {
  const auto config = (wbi::test::source_dir() / "deploy" / "robots" / "arm.yaml").string();
  wbi::sim_rig::InProcessRobot rig(
      "mujoco_sim_robot",
      "robot: " + robot + "\nengine: mujoco\nconfig: " + config +
          "\nlockstep: true\nlockstep_controllers: [pd]\n",
      "robot: " + robot + "\nmethod: backward-difference\ncutoff: 100\n");
  wbi::DdsInterfaceOptions options;
  options.robot = robot;
  options.controller = "pd";
  options.urdf = wbi::test::project_model("arm7.urdf").string();
  options.max_age_s = 5.0;  // lockstep: time is the simulation's
  auto arm = wbi::make_dds_interface(options);
  arm->add_joints({"joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6", "joint_7"});
  rig.start_simulation();
  arm->init(20s);
  const int n = arm->dofs();
  Eigen::VectorXd q_desired(n);
  q_desired << 0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0;
  Eigen::MatrixXd M(6 + n, 6 + n);
  arm->mass_matrix(q_desired, wbi::Transform::Identity(), M);
  const auto gains = wbi::controllers::PdGravityGains::from_inertia(M.bottomRightCorner(n, n), 8.0);
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

TEST(MujocoSimRobot, LockstepPdGravityReachesTheTargetDeterministically) {
  const ArmRun first = run_arm("mj_arm_a", 3000);
  EXPECT_LT(first.final_error, 0.01) << "rad after 3 s";
  const ArmRun second = run_arm("mj_arm_b", 3000);
  EXPECT_EQ(first.final_error, second.final_error);
  ASSERT_EQ(first.torques.size(), 7U * 3000U);
  EXPECT_TRUE(first.torques == second.torques) << "lockstep runs differ";
  std::cout << "arm on MuJoCo over DDS, lockstep, 3 s: max joint error " << first.final_error
            << " rad\n";
}

#endif  // WBI_WITH_MUJOCO

}  // namespace
