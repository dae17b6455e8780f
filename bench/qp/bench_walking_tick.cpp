// Compute time of one walking-controller tick (controllers/walking): the plan's
// sample, the model through the DDS whole-body interface's local model, the QP
// in accelerations and feet wrenches, the command publish — everything after
// the state read. The robot walks 2 m forward (walk_to) in lockstep with the
// estimator, in this process, so each timed tick sees a fresh state of a real
// walk: double and single supports alike. Two robots, every joint controlled:
// the project humanoid (30 joints) and iCub 3 (32 joints, its model from
// ../shared/models; skipped when missing), both in MuJoCo. Counters: the
// steps walked, QP failures, the largest tick.
//   build/bin/wbi_bench_walking --benchmark_format=json
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <wbi/controllers/walking_plan.hpp>
#include <wbi/controllers/walking_planner.hpp>
#include <wbi/controllers/walking_qp.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/sim_rig/humanoid_joints.hpp>
#include <wbi/sim_rig/lockstep_controller_rig.hpp>

namespace {

using namespace std::chrono_literals;
namespace walking = wbi::controllers::walking;

struct WalkingRobot {
  std::string sim_parameters;  // sim_robot's, after robot:
  std::string urdf;
  std::vector<std::string> joints;
  walking::WalkingQpParameters controller;
  walking::WalkingParameters plan;
};

// As deploy/walk.yaml.
WalkingRobot humanoid() {
  const std::string source = WBI_SOURCE_DIR;
  WalkingRobot r;
  r.sim_parameters = "engine: mujoco\nconfig: " + source + "/deploy/robots/humanoid.yaml\n";
  r.urdf = source + "/models/humanoid.urdf";
  r.joints = wbi::sim_rig::humanoid_joints();
  r.plan.max_step_forward = 0.15;
  r.plan.single_support_s = 0.5;
  r.plan.double_support_s = 0.15;
  r.plan.final_double_support_s = 0.5;
  r.plan.step_height = 0.04;
  return r;
}

// As deploy/icub3_walk.yaml.
WalkingRobot icub3() {
  const std::string source = WBI_SOURCE_DIR;
  WalkingRobot r;
  r.sim_parameters = "engine: mujoco\nconfig: " + source + "/deploy/robots/icub3.yaml\n";
  r.urdf = source + "/../shared/models/iCubGenova09/model.urdf";
  r.joints = wbi::sim_rig::icub3_joints();
  r.controller.support = {.x_min = -0.08, .x_max = 0.08, .y_min = -0.03, .y_max = 0.03};
  r.plan.com_height = 0.50;
  r.plan.max_step_forward = 0.19;
  r.plan.single_support_s = 0.38;
  r.plan.double_support_s = 0.12;
  r.plan.final_double_support_s = 0.4;
  r.plan.step_height = 0.05;
  return r;
}

void run_ticks(benchmark::State& state, WalkingRobot walker, const std::string& robot) {
  wbi::sim_rig::LockstepControllerRig rig(robot, walker.sim_parameters, "walking", walker.urdf,
                                          walker.joints);
  wbi::WholeBodyInterface* interface = &rig.robot();
  const Eigen::VectorXd posture = rig.measured_posture();
  walking::WalkingQp qp(*interface, walker.controller, posture);

  // Stand on the measured feet; walk 2 m from t = 0.2 s.
  wbi::RobotState measured(interface->dofs());
  const wbi::Stamp first = interface->state().read_robot_state(measured, wbi::ReadMode::latest);
  qp.start(measured);
  Eigen::Vector3d com;
  interface->com(measured.q, measured.world_H_base, com);
  const auto left = walking::measured_sole(*interface, measured,
                                           interface->frame_index(walker.controller.left_sole));
  const auto right = walking::measured_sole(*interface, measured,
                                            interface->frame_index(walker.controller.right_sole));
  walker.plan.step_width = (left.position - right.position).head<2>().norm();
  walking::WalkingPlan plan(walker.plan);
  plan.stand(0.0, left, right, com);
  const std::string refused = plan.walk_to(0.2, 2.0, 0.0, 0.0);
  if (!refused.empty()) {
    state.SkipWithError(refused.c_str());
    return;
  }
  walking::WalkingReference reference;
  walking::WalkingTargets targets;
  double largest_s = 0.0;
  bool answered = false;  // the first state was read above; lockstep waits for its answer

  for (auto _ : state) {
    if (answered) {
      qp.read_state(wbi::ReadMode::blocking);  // waits for the robot's next tick
    }
    answered = true;
    const wbi::Stamp stamp = qp.read_state(wbi::ReadMode::latest);
    const double t = 1e-9 * static_cast<double>(stamp.source_ns - first.source_ns);
    const auto begin = std::chrono::steady_clock::now();
    plan.sample(t, reference);
    targets.read(reference);
    qp.compute(targets);
    interface->set_control_reference(qp.torques());
    const double tick_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    largest_s = std::max(largest_s, tick_s);
    state.SetIterationTime(tick_s);
  }
  state.counters["qp_failures"] = static_cast<double>(qp.qp_failures());
  state.counters["joints"] = static_cast<double>(walker.joints.size());
  state.counters["largest_tick_us"] = 1e6 * largest_s;
}

void BM_WalkingTick(benchmark::State& state) { run_ticks(state, humanoid(), "bench_walking"); }

void BM_WalkingTickIcub3(benchmark::State& state) {
  const WalkingRobot robot = icub3();
  if (!std::filesystem::exists(robot.urdf)) {
    state.SkipWithError(("skipped: ../shared not found (expected " + robot.urdf + ")").c_str());
    return;
  }
  run_ticks(state, robot, "bench_walking_icub3");
}

// 4000 ticks: 4 s of robot time, the first 7 steps of the walk.
BENCHMARK(BM_WalkingTick)->UseManualTime()->Iterations(4000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WalkingTickIcub3)->UseManualTime()->Iterations(4000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
