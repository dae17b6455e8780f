// Real-time factor of the two engines on the same robot and the same steps:
// iCub 3 standing (deploy/robots/icub3.yaml: sole plates on the ground, eight
// F/T sensors, two IMUs) at a 1 kHz control rate, every joint held by the
// JointController in POSITION mode at the initial posture (20 Hz bandwidth). One
// iteration is one control tick: read → JointController::update → write → step.
// The own plant runs the config's `wbi:` step and substeps (2 × 0.5 ms). MuJoCo
// runs the config's `mujoco:` section (argument 0) or, to show what each option
// costs, the config with options taken back one by one (arguments 1–4):
//   0  the config: 1 × 1 ms, Euler, elliptic cone, joint friction as a torque
//      (joint damping too: the backend applies it explicitly with Euler)
//   1  as 0 with the pyramidal cone
//   2  as 1 with joint friction as frictionloss constraint rows
//   3  as 2 with 2 × 0.5 ms per tick (the config before, 2026-11)
//
// Counters:  rt_factor     simulated s / wall s of the whole tick (target for
//                          MuJoCo: ≥ 20 on one core)
//            rt_factor_cpu simulated s / thread CPU s (less sensitive to the
//                          load of a shared machine than wall time)
//            us_per_tick   wall µs per 1 ms tick
//            base_z        the base height at the end (still standing)
// Needs ../shared/models/iCubGenova09 (skipped with a message otherwise).
// Run: build/bin/wbi_bench_mujoco_sim [--benchmark_format=json]
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>

#include <Eigen/Cholesky>

#include "wbi/actuation/joint_controller.hpp"
#include "wbi/model/crba.hpp"
#include "wbi/model/data.hpp"
#include "wbi/mujoco_sim/mujoco_backend.hpp"
#include "wbi/robot_config/robot_config.hpp"
#include "wbi/sim/sim_backend.hpp"

namespace {

using namespace wbi;

const std::string kConfig = std::string(WBI_SOURCE_DIR) + "/deploy/robots/icub3.yaml";
const std::filesystem::path kShared =
    std::filesystem::path(WBI_SOURCE_DIR).parent_path() / "shared" / "models";

template <typename Backend>
void standing(benchmark::State& state) {
  if (!std::filesystem::is_directory(kShared)) {
    state.SkipWithError(
        ("skipped: ../shared not found (expected " + kShared.string() + ")").c_str());
    return;
  }
  robot_config::RobotConfig config = robot_config::load_robot_config(kConfig);
  using Opt = robot_config::MujocoOptions;
  const std::int64_t variant = state.range(0);  // MuJoCo options taken back (see the top)
  if (variant >= 1) {
    config.mujoco.cone = Opt::Cone::kPyramidal;
  }
  if (variant >= 2) {
    config.mujoco.joint_friction = Opt::JointFriction::kConstraint;
  }
  if (variant >= 3) {
    config.mujoco.timestep = 0.5e-3;
    config.mujoco.substeps = 2;
  }
  Backend sim(config);
  sim.configure();
  sim.activate();
  const auto& d = sim.description();
  // Gains for a 20 Hz bandwidth on each joint's effective inertia at the start,
  // m_j = 1/(M⁻¹)_jj (the URDF's effort limits, 50 kN·m, make the default gains
  // of 10·effort unstable at 1 kHz).
  actuation::JointControllerConfig cc;
  {
    const model::Model& m = sim.model();
    model::Data data(m);
    const Eigen::MatrixXd M = model::mass_matrix(m, data, sim.ground_truth().q);
    const Eigen::MatrixXd M_inv = M.llt().solve(Eigen::MatrixXd::Identity(m.nv, m.nv));
    const double w = 2.0 * M_PI * 20.0;
    for (int j = 0; j < m.n_joints; ++j) {
      const double mj = 1.0 / M_inv(m.base_nv + j, m.base_nv + j);
      actuation::PidGains g;
      g.kp = mj * w * w;
      g.kd = 2.0 * mj * w;
      cc.gains.push_back(g);
    }
  }
  actuation::JointController ctl(d, cc);
  const Eigen::VectorXd q0 = sim.ground_truth().q.tail(d.n_joints());
  actuation::JointCommandBatch batch;
  batch.modes.assign(static_cast<std::size_t>(d.n_joints()), wbi::ControlMode::position);
  batch.values.assign(q0.data(), q0.data() + q0.size());
  ctl.submit(batch, sim.stamp());
  const actuation::Duration period = sim.step_period();

  using Clock = std::chrono::steady_clock;
  auto cpu_seconds = [] {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  };
  std::int64_t ticks = 0;
  const double cpu_start = cpu_seconds();
  const auto start = Clock::now();
  for (auto _ : state) {
    const auto t = sim.stamp();
    sim.read(t, period);
    ctl.update(t, period, sim.readings(), sim.commands());
    sim.write(t, period);
    sim.step();
    ++ticks;
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  const double cpu = cpu_seconds() - cpu_start;
  const double simulated = static_cast<double>(ticks) * static_cast<double>(period.count()) * 1e-9;
  state.counters["rt_factor"] = simulated / wall;
  state.counters["rt_factor_cpu"] = simulated / cpu;
  state.counters["us_per_tick"] = 1e6 * wall / static_cast<double>(ticks);
  state.counters["base_z"] = sim.ground_truth().base_position.z();  // still standing
}

void BM_ICub3Standing_MuJoCo(benchmark::State& state) {
  standing<mujoco_sim::MujocoBackend>(state);
}
void BM_ICub3Standing_OwnPlant(benchmark::State& state) { standing<sim::SimBackend>(state); }

BENCHMARK(BM_ICub3Standing_MuJoCo)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK(BM_ICub3Standing_OwnPlant)->Arg(0)->Unit(benchmark::kMicrosecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
