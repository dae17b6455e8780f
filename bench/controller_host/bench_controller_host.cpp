// What the controller host adds to a tick: host.tick() against calling the
// same controller's update() and sending its command directly, with two
// controllers hosted (the active one and hold) on the project humanoid's 30
// joints. The controller's command is a fixed torque vector, so that its own
// cost is nil and the difference is the host's: parameter staging checks, the
// fallback watch (a steady-clock read either side of update), the copy of the
// command it sends. Both send the command (a DDS publish) once per tick.
//   build/bin/wbi_bench_controller_host --benchmark_format=json
#include <benchmark/benchmark.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <wbi/controllers/controller_host.hpp>
#include <wbi/controllers/controller_types.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

#include "../common/humanoid_joints.hpp"

namespace {

using namespace std::chrono_literals;

// Sends the torques it was configured with: the cheapest controller there is.
class FixedTorque final : public wbi::controllers::Controller {
 public:
  std::vector<wbi::controllers::ParameterSpec> parameters() const override {
    return {{.name = "torque", .default_value = {0.0}, .size = wbi::controllers::kPerJoint}};
  }
  void configure(wbi::WholeBodyInterface& robot,
                 const wbi::controllers::ParameterTable& parameters) override {
    tau_ = Eigen::Map<const Eigen::VectorXd>(parameters.values(0).data(), robot.dofs());
  }
  void activate(const wbi::RobotState&) override {}
  bool update(double, double) override { return true; }
  const Eigen::VectorXd& command() const override { return tau_; }

 private:
  Eigen::VectorXd tau_;
};

struct Humanoid {
  explicit Humanoid(const std::string& robot)
      : rig(robot,
            "robot: " + robot + "\nconfig: " + std::string(WBI_SOURCE_DIR) +
                "/deploy/robots/humanoid.yaml\n",
            "robot: " + robot + "\nbase: topic\nmethod: backward-difference\ncutoff: 50\n") {
    wbi::DdsInterfaceOptions options;
    options.robot = robot;
    options.controller = "host";
    options.urdf = std::string(WBI_SOURCE_DIR) + "/models/humanoid.urdf";
    options.max_age_s = 1e9;  // the simulation is not stepped while timing
    interface = wbi::make_dds_interface(options);
    interface->add_joints(wbi::bench::humanoid_joints());
    rig.start_simulation();
    interface->init(20s);
  }
  wbi::sim_rig::InProcessRobot rig;
  std::unique_ptr<wbi::WholeBodyInterface> interface;
};

void BM_UpdateDirectly(benchmark::State& state) {
  Humanoid robot("bench_host_direct");
  wbi::controllers::ParameterTable parameters("fixed", FixedTorque().parameters());
  parameters.size_for(robot.interface->dofs());
  FixedTorque controller;
  controller.configure(*robot.interface, parameters);
  for (auto _ : state) {
    if (controller.update(0.0, 0.001)) {
      robot.interface->set_control_reference(controller.command());
    }
  }
}

void BM_HostTick(benchmark::State& state) {
  Humanoid robot("bench_host_tick");
  wbi::runtime::StatusReport report;
  wbi::controllers::ControllerHost host(*robot.interface, report, {});
  host.add("fixed", "fixed", std::make_unique<FixedTorque>());
  host.configure("fixed");
  host.add("hold", "hold", wbi::controllers::controller_types().create("hold"));
  host.configure("hold");
  host.set_initial("fixed");
  host.tick(0.0, 0.001);  // activates
  double t = 0.0;
  for (auto _ : state) {
    host.tick(t, 0.001);
    t += 0.001;
  }
  state.counters["fallbacks"] = static_cast<double>(report.counter("fallbacks").value());
}

BENCHMARK(BM_UpdateDirectly)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_HostTick)->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
