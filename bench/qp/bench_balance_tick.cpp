// Compute time of one momentum-balance control tick on the project humanoid
// (30 joints, every one controlled): model quantities through the DDS
// whole-body interface's local model, the torque map, the wrench QP and the
// command publish — everything after the state read. The robot is the
// simulated humanoid in lockstep with the estimator, in this process, so each
// timed tick sees a fresh, realistic state.
//   build/bin/wbi_bench_balance --benchmark_format=json
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>

#include <wbi/controllers/com_sinusoid.hpp>
#include <wbi/controllers/momentum_balance.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/runtime/runner.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

namespace {

using namespace std::chrono_literals;

void BM_MomentumBalanceTick(benchmark::State& state) {
  const std::string source = WBI_SOURCE_DIR;
  const std::string robot = "bench_balance";
  wbi::sim_rig::InProcessRobot rig(
      "bench_balance",
      "robot: " + robot + "\nconfig: " + source +
          "/deploy/robots/humanoid.yaml\nlockstep: true\nlockstep_controllers: [balance]\n",
      "robot: " + robot + "\nbase: topic\nmethod: backward-difference\ncutoff: 50\n");
  wbi::DdsInterfaceOptions options;
  options.robot = robot;
  options.controller = "balance";
  options.urdf = source + "/models/humanoid.urdf";
  options.max_age_s = 5.0;
  auto humanoid = wbi::make_dds_interface(options);
  humanoid->add_joints(
      {"l_hip_pitch",      "l_hip_roll",       "l_hip_yaw",       "l_knee",         "l_ankle_pitch",
       "l_ankle_roll",     "r_hip_pitch",      "r_hip_roll",      "r_hip_yaw",      "r_knee",
       "r_ankle_pitch",    "r_ankle_roll",     "torso_pitch",     "torso_roll",     "torso_yaw",
       "l_shoulder_pitch", "l_shoulder_roll",  "l_shoulder_yaw",  "l_elbow",        "l_wrist_yaw",
       "l_wrist_pitch",    "r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw", "r_elbow",
       "r_wrist_yaw",      "r_wrist_pitch",    "neck_pitch",      "neck_roll",      "neck_yaw"});
  rig.start_simulation();
  humanoid->init(20s);
  Eigen::VectorXd q_posture(humanoid->dofs());
  humanoid->read_estimates(wbi::EstimateKind::joint_position, q_posture);
  wbi::controllers::MomentumBalance balance(*humanoid, {}, q_posture);
  balance.start();
  wbi::controllers::ComSinusoid reference;
  std::int64_t start_ns = -1;

  for (auto _ : state) {
    const wbi::Stamp stamp = balance.read_state(wbi::ReadMode::blocking);
    if (start_ns < 0) {
      start_ns = stamp.source_ns;
    }
    const double t = 1e-9 * static_cast<double>(stamp.source_ns - start_ns);
    if (reference.settling(t)) {
      reference.origin = balance.com_of_state();
    }
    const auto begin = std::chrono::steady_clock::now();
    Eigen::Vector3d x, v, a;
    reference.at(t, x, v, a);
    balance.set_com_reference(x, v, a);
    balance.control();
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
  }
  state.counters["qp_failures"] = static_cast<double>(balance.qp_failures());
  rig.sim().shutdown();
  rig.estimator().shutdown();
}
// 3000 ticks: 3 s of robot time, half a sinusoid period.
BENCHMARK(BM_MomentumBalanceTick)->UseManualTime()->Iterations(3000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
