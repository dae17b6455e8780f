// `wbi param set` as a tool makes it: a HostClient on its own participant sets
// pd's gain_scale on a real controller host (the controller_host component at
// 1 kHz, as a deploy file runs it, on the simulated arm in real time, all in
// this process, loopback); request → staged → applied at a tick → reply.
// Counters p50_us / p99_us / max_us (target: p99 ≤ 2 ms; the wait for the
// next tick alone is up to 1 ms), and the host loop's
// overruns and longest period while it ran. Part of wbi_bench_controller_host.
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <wbi/catalog.hpp>
#include <wbi/controllers/host_client.hpp>
#include <wbi/dds/participant.hpp>
#include <wbi/runtime/clock.hpp>
#include <wbi/runtime/plugins.hpp>
#include <wbi/runtime/registry.hpp>
#include <wbi/runtime/runner.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

#include "../common/percentile.hpp"

namespace {

using namespace std::chrono_literals;

const std::string kSource = WBI_SOURCE_DIR;

void BM_ParameterRoundTrip(benchmark::State& state) {
  const std::string robot = "bench_param_arm";
  wbi::sim_rig::InProcessRobot rig(
      robot, "robot: " + robot + "\nconfig: " + kSource + "/deploy/robots/arm.yaml\n",
      "robot: " + robot + "\nmethod: backward-difference\ncutoff: 50\n");
  wbi::runtime::SystemClock clock;
  wbi::Catalog catalog;  // the built-in plugin's types, as wbi_host has them
  wbi::runtime::load_plugins(catalog, {});
  const auto& registry = catalog.registry<wbi::runtime::Registry>();
  wbi::runtime::ComponentRunner host(
      registry.create("controller_host"),
      wbi::runtime::ComponentContext{"host", "controller_host", &rig.participant(), &clock},
      wbi::runtime::RunnerOptions{.rate_hz = 1000.0});
  rig.start_simulation();
  host.configure(wbi::runtime::Parameters::from_string(
      "robot: " + robot + "\nurdf: " + kSource +
      "/models/arm7.urdf\n"
      "joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6, joint_7]\n"
      "progress_period_s: 0\n"
      "controllers:\n"
      "  pd: {type: pd_gravity, target: [0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0]}\n"
      "active: pd\n"));
  host.activate();
  wbi::dds::Participant participant("bench_param_client");
  wbi::controllers::HostClient client(participant, robot, 5s);
  client.list();  // discovery and matching, not timed
  std::vector<double> round_trips_us;
  round_trips_us.reserve(static_cast<std::size_t>(state.max_iterations));
  // Arg 1: each request at a random time in the loop's period, as a person or
  // script would send it. Arg 0: back to back, so each request arrives just
  // after the tick that answered the last one and waits almost a whole period
  // for the next (the slowest phase).
  const bool random_phase = state.range(0) == 1;
  std::minstd_rand random(36);
  std::uniform_int_distribution<int> pause_us(0, 999);
  double scale = 1.0;
  for (auto _ : state) {
    if (random_phase) {
      std::this_thread::sleep_for(std::chrono::microseconds(pause_us(random)));
    }
    scale = scale == 1.0 ? 0.9 : 1.0;
    const auto begin = std::chrono::steady_clock::now();
    client.set_parameter("pd", "gain_scale", {scale});
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    state.SetIterationTime(s);
    round_trips_us.push_back(1e6 * s);
  }
  state.counters["p50_us"] = wbi::bench::percentile(round_trips_us, 0.5);
  state.counters["p99_us"] = wbi::bench::percentile(round_trips_us, 0.99);
  state.counters["max_us"] = wbi::bench::percentile(round_trips_us, 1.0);
  const wbi::runtime::LoopStats loop = host.stats();
  state.counters["loop_overruns"] = static_cast<double>(loop.overruns);
  state.counters["loop_period_max_us"] = 1e6 * loop.period_max_s;
  host.shutdown();
  rig.sim().shutdown();
  rig.estimator().shutdown();
}

BENCHMARK(BM_ParameterRoundTrip)
    ->ArgName("random_phase")
    ->Arg(1)
    ->Arg(0)
    ->UseManualTime()
    ->Iterations(1000)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
