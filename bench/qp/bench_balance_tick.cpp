// Compute time of one momentum-balance control tick: model quantities through
// the DDS whole-body interface's local model, the torque map, the wrench QP and
// the command publish — everything after the state read (the time), and the
// state read itself (counter read_state_us: a second read of the estimate the
// blocking read waited for, so no waiting is counted). Two robots, every
// joint controlled: the project humanoid (30 joints, the own plant) and iCub 3
// (32 joints, MuJoCo, its model from ../shared/models; skipped when missing).
// The robot is simulated in lockstep with the estimator, in this process, so
// each timed tick sees a fresh, realistic state.
//   build/bin/wbi_bench_balance --benchmark_format=json
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <wbi/controllers/com_sinusoid.hpp>
#include <wbi/controllers/momentum_balance.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/runtime/runner.hpp>

#include <wbi/sim_rig/humanoid_joints.hpp>
#include <wbi/sim_rig/lockstep_controller_rig.hpp>

namespace {

using namespace std::chrono_literals;

struct BalancedRobot {
  std::string sim_parameters;  // sim_robot's, after robot:
  std::string urdf;
  std::vector<std::string> joints;
  wbi::controllers::MomentumBalanceParameters parameters;
  double com_amplitude = 0.05;  // [m]
};

BalancedRobot humanoid() {
  const std::string source = WBI_SOURCE_DIR;
  BalancedRobot r;
  r.sim_parameters = "config: " + source + "/deploy/robots/humanoid.yaml\n";
  r.urdf = source + "/models/humanoid.urdf";
  r.joints = wbi::sim_rig::humanoid_joints();
  return r;
}

// As deploy/icub3_balance.yaml.
BalancedRobot icub3() {
  const std::string source = WBI_SOURCE_DIR;
  BalancedRobot r;
  r.sim_parameters = "engine: mujoco\nconfig: " + source + "/deploy/robots/icub3.yaml\n";
  r.urdf = source + "/../shared/models/iCubGenova09/model.urdf";
  r.joints = wbi::sim_rig::icub3_joints();
  r.parameters.foot_x_min = -0.08;
  r.parameters.foot_x_max = 0.08;
  r.parameters.foot_y_min = -0.03;
  r.parameters.foot_y_max = 0.03;
  r.com_amplitude = 0.03;
  return r;
}

void run_ticks(benchmark::State& state, const BalancedRobot& balanced, const std::string& robot) {
  wbi::sim_rig::LockstepControllerRig rig(robot, balanced.sim_parameters, "balance", balanced.urdf,
                                          balanced.joints);
  wbi::WholeBodyInterface* interface = &rig.robot();
  const Eigen::VectorXd q_posture = rig.measured_posture();
  wbi::controllers::MomentumBalance balance(*interface, balanced.parameters, q_posture);
  balance.start();
  wbi::controllers::ComSinusoid reference;
  reference.amplitude = balanced.com_amplitude;
  std::int64_t start_ns = -1;
  double read_s = 0.0;

  for (auto _ : state) {
    balance.read_state(wbi::ReadMode::blocking);  // waits for the robot's next tick
    // The state read alone: the same estimate once more, now that it is here.
    const auto read_begin = std::chrono::steady_clock::now();
    const wbi::Stamp stamp = balance.read_state(wbi::ReadMode::latest);
    read_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - read_begin).count();
    if (start_ns < 0) {
      start_ns = stamp.source_ns;
    }
    const double t = 1e-9 * static_cast<double>(stamp.source_ns - start_ns);
    reference.follow(
        t, [&] { return balance.com_of_state(); }, [&] { return balance.feet_center_of_state(); });
    const auto begin = std::chrono::steady_clock::now();
    Eigen::Vector3d x, v, a;
    reference.at(t, x, v, a);
    balance.set_com_reference(x, v, a);
    balance.control();
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
  }
  state.counters["read_state_us"] = 1e6 * read_s / static_cast<double>(state.iterations());
  state.counters["qp_failures"] = static_cast<double>(balance.qp_failures());
  state.counters["joints"] = static_cast<double>(balanced.joints.size());
}

void BM_MomentumBalanceTick(benchmark::State& state) {
  run_ticks(state, humanoid(), "bench_balance");
}

void BM_MomentumBalanceTickIcub3(benchmark::State& state) {
  const BalancedRobot robot = icub3();
  if (!std::filesystem::exists(robot.urdf)) {
    state.SkipWithError(("skipped: ../shared not found (expected " + robot.urdf + ")").c_str());
    return;
  }
  run_ticks(state, robot, "bench_balance_icub3");
}

// 3000 ticks: 3 s of robot time, half a sinusoid period.
BENCHMARK(BM_MomentumBalanceTick)->UseManualTime()->Iterations(3000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MomentumBalanceTickIcub3)
    ->UseManualTime()
    ->Iterations(3000)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
