// The controller host's costs and delays, on loopback in this process:
//
// BM_UpdateDirectly, BM_HostTick: what the host adds to a tick, host.tick()
//   against calling the same controller's update() and sending its command
//   directly, with two controllers hosted (the active one and hold) on iCub 3's
//   32 joints (../shared/models; skipped when missing). The controller's
//   command is a fixed torque vector, so that its own cost is nil and the
//   difference is the host's: parameter staging checks, the fallback watch (a
//   steady-clock read either side of update), the copy of the command it
//   sends. Both send the command (a DDS publish) once per tick. Target: the
//   difference ≤ 2 µs per tick. BM_HostOverheadPaired: the two in turn, tick
//   by tick, and the difference of their medians (less sensitive to load).
// BM_HostOverheadThreeControllers: the same with three active controllers, a
//   planner chained to the legs' input, the arms beside them, hold on the rest.
// BM_SwitchTicks: a switch requested from another thread while the loop ticks
//   at 1 kHz (the same robot and host, two fixed-torque controllers and hold):
//   ticks from the request to the new controller's first update (counters
//   ticks_to_switch_mean / _max; target ≤ 1), and the request's wall time.
// BM_ParameterRoundTrip (bench_parameter_round_trip.cpp): `wbi param set`
//   against a real host at 1 kHz.
//
// Runs on WBI_DOMAIN_ID, default 230 here (no test or other benchmark uses it).
//   build/bin/wbi_bench_controller_host --benchmark_format=json
#include <benchmark/benchmark.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include <wbi/controllers/controller_host.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

#include "../common/percentile.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::controllers::ControllerHost;

const std::string kSource = WBI_SOURCE_DIR;
const std::string kIcub3Urdf = kSource + "/../shared/models/iCubGenova09/model.urdf";
const std::vector<std::string> kIcub3Joints{
    "torso_roll",       "torso_pitch",     "torso_yaw",      "l_shoulder_pitch", "l_shoulder_roll",
    "l_shoulder_yaw",   "l_elbow",         "l_wrist_prosup", "l_wrist_pitch",    "l_wrist_yaw",
    "r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw", "r_elbow",          "r_wrist_prosup",
    "r_wrist_pitch",    "r_wrist_yaw",     "neck_pitch",     "neck_roll",        "neck_yaw",
    "l_hip_pitch",      "l_hip_roll",      "l_hip_yaw",      "l_knee",           "l_ankle_pitch",
    "l_ankle_roll",     "r_hip_pitch",     "r_hip_roll",     "r_hip_yaw",        "r_knee",
    "r_ankle_pitch",    "r_ankle_roll"};

// Sends the torques it was configured with: the cheapest controller there is.
// first_tick (optional): set to *ticks at its first update after an activation.
class FixedTorque final : public wbi::controllers::Controller {
 public:
  explicit FixedTorque(const std::atomic<std::uint64_t>* ticks = nullptr,
                       std::atomic<std::uint64_t>* first_tick = nullptr)
      : ticks_(ticks), first_tick_(first_tick) {}
  std::vector<wbi::controllers::ParameterSpec> parameters() const override {
    return {{.name = "torque", .default_value = {0.0}, .size = wbi::controllers::kPerJoint}};
  }
  void configure(wbi::WholeBodyInterface& robot,
                 const wbi::controllers::ParameterTable& parameters) override {
    tau_ = Eigen::Map<const Eigen::VectorXd>(parameters.values(0).data(), robot.dofs());
  }
  void activate(const wbi::RobotState&) override { first_ = true; }
  bool update(double, double) override {
    if (first_ && first_tick_) {
      first_tick_->store(ticks_->load(std::memory_order_relaxed), std::memory_order_release);
    }
    first_ = false;
    return true;
  }
  const Eigen::VectorXd& command() const override { return tau_; }

 private:
  Eigen::VectorXd tau_;
  const std::atomic<std::uint64_t>* ticks_;
  std::atomic<std::uint64_t>* first_tick_;
  bool first_ = false;
};

// iCub 3 with its base fixed, simulated in real time by the own plant, and the
// interface to its 32 joints.
struct Icub3 {
  explicit Icub3(const std::string& robot)
      : rig(robot,
            "robot: " + robot + "\nconfig: " + kSource + "/deploy/robots/icub3_fixed_base.yaml\n",
            "robot: " + robot + "\nbase: topic\nmethod: backward-difference\ncutoff: 50\n") {
    wbi::DdsInterfaceOptions options;
    options.robot = robot;
    options.controller = "host";
    options.urdf = kIcub3Urdf;
    options.max_age_s = 1e9;  // the state is not read while timing
    interface = wbi::make_dds_interface(options);
    interface->add_joints(kIcub3Joints);
    rig.start_simulation();
    interface->init(20s);
  }
  ~Icub3() {
    rig.sim().shutdown();
    rig.estimator().shutdown();
  }
  wbi::sim_rig::InProcessRobot rig;
  std::unique_ptr<wbi::WholeBodyInterface> interface;
};

bool have_icub3(benchmark::State& state) {
  if (!std::filesystem::exists(kIcub3Urdf)) {
    state.SkipWithError(("skipped: ../shared not found (expected " + kIcub3Urdf + ")").c_str());
    return false;
  }
  return true;
}

void BM_UpdateDirectly(benchmark::State& state) {
  if (!have_icub3(state)) {
    return;
  }
  Icub3 robot("bench_host_direct");
  wbi::controllers::ParameterTable parameters("fixed", FixedTorque().parameters());
  parameters.size_for(robot.interface->dofs());
  FixedTorque controller;
  controller.configure(*robot.interface, parameters);
  for (auto _ : state) {
    if (controller.update(0.0, 0.001)) {
      robot.interface->set_control_reference(controller.command());
    }
  }
  state.counters["joints"] = static_cast<double>(robot.interface->dofs());
}

// The two controllers of the overhead benchmarks: FixedTorque active, hold
// configured beside it; the first tick activates.
void host_fixed_and_hold(ControllerHost& host) {
  host.add("fixed", "fixed", std::make_unique<FixedTorque>());
  host.configure("fixed");
  host.add("hold", "hold", wbi::controllers::make_hold_controller());
  host.configure("hold");
  host.set_initial("fixed");
  host.tick(0.0, 0.001);
}

void BM_HostTick(benchmark::State& state) {
  if (!have_icub3(state)) {
    return;
  }
  Icub3 robot("bench_host_tick");
  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  ControllerHost host(*robot.interface, report, events, {});
  host_fixed_and_hold(host);
  double t = 0.0;
  for (auto _ : state) {
    host.tick(t, 0.001);
    t += 0.001;
  }
  state.counters["joints"] = static_cast<double>(robot.interface->dofs());
  state.counters["controllers"] = static_cast<double>(host.list().size());
  state.counters["fallbacks"] = static_cast<double>(report.counter("fallbacks").value());
}

// Ticks `direct` (the controllers' updates and the send, by hand) and the
// host in turn, each timed on its own, and sets the counters of both and of
// their difference (the host's part) from their medians.
template <class Direct>
void time_paired(benchmark::State& state, Direct&& direct, ControllerHost& host) {
  std::vector<double> direct_ns, host_ns;
  direct_ns.reserve(static_cast<std::size_t>(state.max_iterations));
  host_ns.reserve(static_cast<std::size_t>(state.max_iterations));
  double t = 0.001;
  for (auto _ : state) {
    const auto begin = std::chrono::steady_clock::now();
    direct(t);
    const auto between = std::chrono::steady_clock::now();
    host.tick(t, 0.001);
    const auto end = std::chrono::steady_clock::now();
    direct_ns.push_back(std::chrono::duration<double, std::nano>(between - begin).count());
    host_ns.push_back(std::chrono::duration<double, std::nano>(end - between).count());
    t += 0.001;
  }
  const double direct_p50 = wbi::bench::percentile(direct_ns, 0.5);
  const double host_p50 = wbi::bench::percentile(host_ns, 0.5);
  state.counters["direct_p50_ns"] = direct_p50;
  state.counters["host_p50_ns"] = host_p50;
  state.counters["overhead_p50_ns"] = host_p50 - direct_p50;
  state.counters["direct_p99_ns"] = wbi::bench::percentile(direct_ns, 0.99);
  state.counters["host_p99_ns"] = wbi::bench::percentile(host_ns, 0.99);
  state.counters["active"] = static_cast<double>(host.active_controllers().size());
}

// The same two, tick by tick in turn (direct, then the host), each timed on
// its own: the machine's load (the simulation runs on the other core) and the
// publish's own spread fall on both alike, so the difference of the medians
// is the host's part. Counter overhead_p50_ns (target ≤ 2000 ns).
void BM_HostOverheadPaired(benchmark::State& state) {
  if (!have_icub3(state)) {
    return;
  }
  Icub3 robot("bench_host_paired");
  wbi::controllers::ParameterTable parameters("fixed", FixedTorque().parameters());
  parameters.size_for(robot.interface->dofs());
  FixedTorque direct;
  direct.configure(*robot.interface, parameters);
  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  ControllerHost host(*robot.interface, report, events, {});
  host_fixed_and_hold(host);
  time_paired(
      state,
      [&](double t) {
        if (direct.update(t, 0.001)) {
          robot.interface->set_control_reference(direct.command());
        }
      },
      host);
  state.counters["joints"] = static_cast<double>(robot.interface->dofs());
  state.counters["controllers"] = static_cast<double>(host.list().size());
  state.counters["fallbacks"] = static_cast<double>(report.counter("fallbacks").value());
}

// One switch per iteration, a ↔ b, requested as the host's service does
// (request_switch, waiting for the loop), the loop ticking at 1 kHz on its own
// thread. Ticks are counted by the loop before each tick(): the request is made
// while tick n runs or after it, so a switch applied by the next tick counts 1.
void BM_SwitchTicks(benchmark::State& state) {
  if (!have_icub3(state)) {
    return;
  }
  Icub3 robot("bench_host_switch");
  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  ControllerHost host(*robot.interface, report, events, {});
  std::atomic<std::uint64_t> ticks{0}, first_a{0}, first_b{0};
  host.add("a", "fixed", std::make_unique<FixedTorque>(&ticks, &first_a));
  host.configure("a");
  host.add("b", "fixed", std::make_unique<FixedTorque>(&ticks, &first_b));
  host.configure("b");
  host.add("hold", "hold", wbi::controllers::make_hold_controller());
  host.configure("hold");
  host.set_initial("a");
  std::atomic<bool> stop{false};
  std::thread loop([&] {
    auto next = std::chrono::steady_clock::now();
    while (!stop.load()) {
      const std::uint64_t n = ticks.fetch_add(1) + 1;
      host.tick(0.001 * static_cast<double>(n), 0.001);
      next += 1ms;
      std::this_thread::sleep_until(next);
    }
  });
  while (ticks.load() < 10) {
    std::this_thread::sleep_for(1ms);
  }
  std::vector<double> switch_ticks;
  bool to_b = true;
  for (auto _ : state) {
    std::atomic<std::uint64_t>& first = to_b ? first_b : first_a;
    first.store(0);
    const std::uint64_t requested_at = ticks.load();
    const auto begin = std::chrono::steady_clock::now();
    const auto result =
        to_b ? host.request_switch({"b"}, {"a"}) : host.request_switch({"a"}, {"b"});
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
    if (!result.done) {
      state.SkipWithError(result.text.c_str());
      break;
    }
    switch_ticks.push_back(static_cast<double>(first.load(std::memory_order_acquire)) -
                           static_cast<double>(requested_at));
    to_b = !to_b;
    std::this_thread::sleep_for(std::chrono::microseconds(300));  // request mid-period
  }
  stop.store(true);
  loop.join();
  double sum = 0.0;
  for (const double n : switch_ticks) {
    sum += n;
  }
  state.counters["ticks_to_switch_mean"] =
      switch_ticks.empty() ? 0.0 : sum / static_cast<double>(switch_ticks.size());
  state.counters["ticks_to_switch_max"] = wbi::bench::percentile(switch_ticks, 1.0);
  state.counters["joints"] = static_cast<double>(robot.interface->dofs());
  state.counters["fallbacks"] = static_cast<double>(report.counter("fallbacks").value());
}

// Three controllers active at once, one of them chained: a planner writes a
// 3-value point per tick into the legs' reference input (same tick, no DDS),
// the legs (12 joints) read it and send fixed torques, the upper body (torso,
// arms, neck: 20 joints) sends its own; hold holds nothing. Direct: the same three updates
// (the point through the same output and input), the two commands copied
// into one and sent. Counter overhead_p50_ns (target ≤ 2000 ns).
class FixedPlanner final : public wbi::controllers::Controller {
 public:
  std::vector<wbi::controllers::ParameterSpec> parameters() const override { return {}; }
  std::vector<wbi::controllers::ReferenceSpec> outputs() const override {
    return {{.name = "ref", .size = 3}};
  }
  void bind_outputs(std::span<wbi::controllers::ReferenceOutput* const> outputs) override {
    output_ = outputs[0];
  }
  bool commands_joints() const override { return false; }
  void configure(wbi::WholeBodyInterface&, const wbi::controllers::ParameterTable&) override {}
  void activate(const wbi::RobotState&) override {}
  bool update(double time_s, double) override {
    const double point[3] = {time_s, 0.0, 0.0};
    output_->write(static_cast<std::int64_t>(time_s * 1e9), point);
    return true;
  }
  const Eigen::VectorXd& command() const override { return none_; }
  wbi::controllers::ReferenceOutput* output_ = nullptr;

 private:
  Eigen::VectorXd none_;
};

class FixedFollower final : public wbi::controllers::Controller {
 public:
  std::vector<wbi::controllers::ParameterSpec> parameters() const override { return {}; }
  std::vector<wbi::controllers::ReferenceSpec> references() const override {
    return {{.name = "ref", .size = 3}};
  }
  void bind_references(std::span<wbi::controllers::ReferenceInput* const> inputs) override {
    input_ = inputs[0];
  }
  void configure(wbi::WholeBodyInterface& robot, const wbi::controllers::ParameterTable&) override {
    tau_ = Eigen::VectorXd::Constant(robot.dofs(), 0.5);
  }
  void activate(const wbi::RobotState&) override {}
  bool update(double time_s, double) override {
    input_->at(static_cast<std::int64_t>(time_s * 1e9), [] { return Eigen::Vector3d::Zero(); });
    tau_[0] = input_->position()[0];
    return true;
  }
  const Eigen::VectorXd& command() const override { return tau_; }
  wbi::controllers::ReferenceInput* input_ = nullptr;

 private:
  Eigen::VectorXd tau_;
};

std::vector<std::string> icub3_joints(std::size_t from, std::size_t count) {
  return {kIcub3Joints.begin() + static_cast<long>(from),
          kIcub3Joints.begin() + static_cast<long>(from + count)};
}

void BM_HostOverheadThreeControllers(benchmark::State& state) {
  if (!have_icub3(state)) {
    return;
  }
  Icub3 robot("bench_host_three");
  const int n = robot.interface->dofs();
  // Direct: the same controllers, chained by hand.
  wbi::controllers::ParameterTable none("none", {});
  wbi::controllers::ParameterTable fixed("fixed", FixedTorque().parameters());
  fixed.size_for(n);
  FixedPlanner planner;
  FixedFollower legs;
  FixedTorque arms;
  wbi::controllers::ReferenceOutput output("planner/ref", planner.outputs()[0]);
  wbi::controllers::ReferenceInput input("legs/ref", legs.references()[0]);
  output.connect(input);
  planner.output_ = &output;
  legs.input_ = &input;
  legs.configure(*robot.interface, none);
  arms.configure(*robot.interface, fixed);
  std::vector<int> leg_joints, arm_joints;
  for (int j = 20; j < 32; ++j) {
    leg_joints.push_back(j);
  }
  for (int j = 0; j < 20; ++j) {
    arm_joints.push_back(j);
  }
  Eigen::VectorXd command = Eigen::VectorXd::Zero(n);
  // The host: the same three (hold configured, holding nothing).
  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  ControllerHost host(*robot.interface, report, events, {});
  host.add("planner", "planner", std::make_unique<FixedPlanner>());
  host.configure("planner");
  host.add("legs", "follower", std::make_unique<FixedFollower>());
  host.set_joints("legs", icub3_joints(20, 12));
  host.configure("legs");
  host.chain("legs", "ref", "planner", "ref");
  host.add("arms", "fixed", std::make_unique<FixedTorque>());
  host.set_joints("arms", icub3_joints(0, 20));
  host.configure("arms");
  host.add("hold", "hold", wbi::controllers::make_hold_controller());
  host.configure("hold");
  host.set_initial(std::vector<std::string>{"legs", "arms"});
  host.tick(0.0, 0.001);
  time_paired(
      state,
      [&](double t) {
        planner.update(t, 0.001);
        legs.update(t, 0.001);
        arms.update(t, 0.001);
        for (const int j : leg_joints) {
          command[j] = legs.command()[j];
        }
        for (const int j : arm_joints) {
          command[j] = arms.command()[j];
        }
        robot.interface->set_control_reference(command);
      },
      host);
  state.counters["joints"] = n;
  state.counters["fallbacks"] = static_cast<double>(report.counter("fallbacks").value());
}

BENCHMARK(BM_UpdateDirectly)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_HostTick)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_HostOverheadPaired)->Iterations(50000)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_HostOverheadThreeControllers)->Iterations(50000)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_SwitchTicks)->UseManualTime()->Iterations(200)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  if (std::getenv("WBI_DOMAIN_ID") == nullptr) {
    setenv("WBI_DOMAIN_ID", "230", 1);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    return 1;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
