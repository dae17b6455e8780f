// A third simulation engine for the tests, registered by name beside the
// built-in ones: one joint, q̈ = τ.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <wbi/runtime/registry.hpp>
#include <wbi/sim_robot/sim_robot.hpp>

namespace wbi::test {

namespace actuation = wbi::actuation;

inline constexpr double kDt = 1e-3;  // the toy's control period [s]

// One joint, q̈ = τ, semi-implicit Euler over one control period per step().
// With a counter, each step() also notes its value (on the driver's loop thread).
class ToySimulation final : public actuation::SimulationBackend {
 public:
  using Counter = long (*)();
  explicit ToySimulation(Counter counter) : counter_(counter), marks_(1024, 0) {}
  // The counter's growth over step k (sense → clock → control → actuate → step), k ≥ 1.
  long growth_in_step(std::size_t k) const { return marks_[k] - marks_[k - 1]; }
  std::int64_t steps() const { return steps_; }

  actuation::Duration step_period() const override { return actuation::Duration(1'000'000); }
  double time() const override { return static_cast<double>(steps_) * kDt; }
  actuation::Time stamp() const override { return actuation::Time(steps_ * 1'000'000); }
  const actuation::GroundTruth& ground_truth() const override { return truth_; }

 protected:
  actuation::BackendDescription on_configure() override {
    actuation::BackendDescription d;
    d.robot = "toy";
    d.urdf = "toy.urdf";
    d.joint_names = {"a"};
    d.position_lower = {-100.0};
    d.position_upper = {100.0};
    d.velocity_limit = {100.0};
    d.effort_limit = {50.0};
    truth_.q = truth_.nu = truth_.dnu = truth_.tau = truth_.tau_actuator = Eigen::VectorXd::Zero(1);
    return d;
  }
  void on_read(actuation::Time, actuation::Duration, actuation::SensorReadings& out) override {
    out.position = truth_.q;
    out.velocity = truth_.nu;
    out.joint_stamp = stamp();
  }
  void on_write(actuation::Time, actuation::Duration, const actuation::JointCommands& in) override {
    tau_ = in.mode[0] == actuation::OutputMode::kTorque ? in.value[0] : 0.0;
  }
  void on_step() override {
    truth_.nu[0] += tau_ * kDt;
    truth_.q[0] += truth_.nu[0] * kDt;
    truth_.tau[0] = tau_;
    if (counter_ != nullptr) {
      marks_[static_cast<std::size_t>(steps_) % marks_.size()] = counter_();
    }
    ++steps_;
    truth_.time = time();
  }

 private:
  Counter counter_;
  std::vector<long> marks_;  // [step] the counter after it
  actuation::GroundTruth truth_;
  double tau_ = 0.0;
  std::int64_t steps_ = 0;
};

struct Seen {
  std::string robot;
  std::string config;
  ToySimulation* engine = nullptr;  // owned by the component
};

// The built-in engines and "toy", whose instances count with `counter`.
inline wbi::runtime::Registry registry_with_toy(Seen& seen,
                                                ToySimulation::Counter counter = nullptr) {
  auto engines = wbi::sim_robot::builtin_engines();
  engines.add("toy", [&seen, counter](const wbi::sim_robot::EngineContext& context) {
    auto engine = std::make_unique<ToySimulation>(counter);
    seen = {context.robot, context.config.string(), engine.get()};
    return engine;
  });
  wbi::runtime::Registry registry;
  wbi::sim_robot::register_components(
      registry, std::make_shared<const wbi::sim_robot::EngineRegistry>(std::move(engines)));
  return registry;
}

}  // namespace wbi::test
