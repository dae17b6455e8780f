// Simulated seconds per wall second of the humanoid standing on 8 contact points
// (the corners of the two foot boxes) at a 1 kHz control rate, joint PD in
// POSITION_DIRECT at the initial posture, IMU and two F/T sensors on.
//
// Counters:
//   rt_factor        simulated s / wall s of the whole robot-side tick
//                    (read → JointController::update → write → step)
//   plant_rt_factor  simulated s / wall s of SimBackend::step() alone (the plant;
//                    target ≥ 20)
//   us_per_tick      wall µs per 1 ms tick (whole loop)
// Argument: integration substeps per 1 ms step (2 is the default).
// Run: build/bin/wbi_bench_sim [--benchmark_format=json]
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>

#include "wbi/actuation/joint_controller.hpp"
#include "wbi/sim/sim_backend.hpp"

namespace {

using namespace wbi;

void BM_HumanoidStanding(benchmark::State& state) {
  robot_config::RobotConfig c;
  c.urdf = std::string(WBI_SOURCE_DIR) + "/models/humanoid.urdf";
  c.initial_base_position = Eigen::Vector3d(0.0, 0.0, 0.555);
  c.place_on_ground = true;
  c.wbi.substeps = static_cast<int>(state.range(0));
  c.imus.push_back({"imu", "imu_frame", 0.0, 0.0});
  c.force_torque.push_back({"l_foot_ft", "l_foot_ft_sensor", 0.0, 0.0});
  c.force_torque.push_back({"r_foot_ft", "r_foot_ft_sensor", 0.0, 0.0});
  sim::SimBackend sim(c);
  sim.configure();
  sim.activate();
  const auto& d = sim.description();
  actuation::JointControllerConfig cc;
  for (int j = 0; j < d.n_joints(); ++j) {
    actuation::PidGains g;
    g.kp = 10.0 * d.effort_limit[static_cast<std::size_t>(j)];
    g.kd = g.kp / 200.0;
    cc.gains.push_back(g);
  }
  actuation::JointController ctl(d, cc);
  const Eigen::VectorXd q0 = sim.ground_truth().q.tail(d.n_joints());
  actuation::JointCommandBatch batch;
  batch.modes.assign(static_cast<std::size_t>(d.n_joints()), wbi::ControlMode::position_direct);
  batch.values.assign(q0.data(), q0.data() + q0.size());
  const actuation::Duration period(1000000);

  using Clock = std::chrono::steady_clock;
  Clock::duration plant{0};
  std::int64_t ticks = 0;
  const auto start = Clock::now();
  for (auto _ : state) {
    const auto t = sim.stamp();
    sim.read(t, period);
    ctl.submit(batch, t);
    ctl.update(t, period, sim.readings(), sim.commands());
    sim.write(t, period);
    const auto p0 = Clock::now();
    sim.step();
    plant += Clock::now() - p0;
    ++ticks;
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  const double simulated = static_cast<double>(ticks) * c.wbi.step;
  state.counters["rt_factor"] = simulated / wall;
  state.counters["plant_rt_factor"] = simulated / std::chrono::duration<double>(plant).count();
  state.counters["us_per_tick"] = 1e6 * wall / static_cast<double>(ticks);
  state.counters["contact_points"] = static_cast<double>(sim.ground_truth().contact_points.size());
  state.counters["base_height"] = sim.ground_truth().base_position.z();
}
BENCHMARK(BM_HumanoidStanding)->Arg(1)->Arg(2)->Arg(4)->MinTime(2.0)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
