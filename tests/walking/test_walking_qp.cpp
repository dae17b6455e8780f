// The walking QP (controllers/walking) driven by its plan in this process, on
// the project humanoid simulated in lockstep in MuJoCo, over real DDS: it
// takes the plan's steps without falling and without a failed QP, each foot
// lands near its footstep, and a tick (the plan's sample, the model, the QP)
// allocates nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <wbi/controllers/walking_plan.hpp>
#include <wbi/controllers/walking_planner.hpp>
#include <wbi/controllers/walking_qp.hpp>
#include <wbi/sim_rig/humanoid_joints.hpp>
#include <wbi/sim_rig/lockstep_controller_rig.hpp>

#include "allocation_counter.hpp"
#include "test_support.hpp"

namespace {

namespace walking = wbi::controllers::walking;

TEST(WalkingQp, TheHumanoidWalksItsPlanWithoutAllocating) {
  wbi::sim_rig::LockstepControllerRig rig(
      "walking_qp_humanoid",
      "engine: mujoco\nconfig: " +
          (wbi::test::source_dir() / "deploy" / "robots" / "humanoid.yaml").string() + "\n",
      "walking", wbi::test::project_model("humanoid.urdf").string(),
      wbi::sim_rig::humanoid_joints());
  wbi::WholeBodyInterface& robot = rig.robot();
  walking::WalkingQpParameters parameters;
  walking::WalkingQp qp(robot, parameters, rig.measured_posture());

  wbi::RobotState measured(robot.dofs());
  const wbi::Stamp first = robot.state().read_robot_state(measured, wbi::ReadMode::latest);
  qp.start(measured);
  Eigen::Vector3d com;
  robot.com(measured.q, measured.world_H_base, com);
  walking::WalkingParameters plan_parameters;
  plan_parameters.max_step_forward = 0.15;
  plan_parameters.single_support_s = 0.5;
  plan_parameters.double_support_s = 0.15;
  plan_parameters.final_double_support_s = 0.5;
  const auto left =
      walking::measured_sole(robot, measured, robot.frame_index(parameters.left_sole));
  const auto right =
      walking::measured_sole(robot, measured, robot.frame_index(parameters.right_sole));
  plan_parameters.step_width = (left.position - right.position).head<2>().norm();
  plan_parameters.com_height = com.z() - left.position.z();
  walking::WalkingPlan plan(plan_parameters);
  plan.stand(0.0, left, right, com);
  ASSERT_EQ(plan.walk_to(0.2, 0.6, 0.0, 0.0), "");
  const double end = plan.end_time() + 0.5;

  walking::WalkingReference reference;
  walking::WalkingTargets targets;
  long allocations = 0;
  int ticks = 0, touchdowns = 0;
  double lowest_base = 1e9, largest_touchdown_error = 0.0;
  double last_weight[2] = {1.0, 1.0};
  for (double t = 0.0; t < end; ++ticks) {
    if (ticks > 0) {
      qp.read_state(wbi::ReadMode::blocking);  // the robot's next tick
    }
    const wbi::Stamp stamp = qp.read_state(wbi::ReadMode::latest);
    t = 1e-9 * static_cast<double>(stamp.source_ns - first.source_ns);
    const long before = wbi::test::thread_allocation_count();
    plan.sample(t, reference);
    targets.read(reference);
    qp.compute(targets);
    if (ticks >= 10) {  // the first ticks size the model's caches
      allocations += wbi::test::thread_allocation_count() - before;
    }
    robot.set_control_reference(qp.torques());

    lowest_base = std::min(lowest_base, qp.state().world_H_base(2, 3));
    for (int f = 0; f < 2; ++f) {
      const double w = targets.contact_weight[f];
      if (last_weight[f] == 0.0 && w > 0.0) {
        ++touchdowns;
        const auto& foot = qp.foot(f == 0 ? walking::Foot::left : walking::Foot::right);
        largest_touchdown_error =
            std::max(largest_touchdown_error, (foot.position - targets.feet[f].position).norm());
      }
      last_weight[f] = w;
    }
  }
  EXPECT_EQ(allocations, 0) << "heap allocations in " << ticks << " walking ticks";
  EXPECT_EQ(qp.qp_failures(), 0u);
  EXPECT_EQ(touchdowns, static_cast<int>(plan.footsteps().size()));
  EXPECT_GE(touchdowns, 4);
  EXPECT_LT(largest_touchdown_error, 0.02) << "m";
  // Standing, the base is 0.5 m up: a fall would bring it far lower.
  EXPECT_GT(lowest_base, 0.4) << "m";
  const Eigen::Vector3d middle =
      0.5 * (qp.foot(walking::Foot::left).position + qp.foot(walking::Foot::right).position);
  EXPECT_NEAR(middle.x() - 0.5 * (left.position + right.position).x(), 0.6, 0.06);
}

}  // namespace
