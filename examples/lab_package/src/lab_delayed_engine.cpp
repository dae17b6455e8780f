#include "lab_delayed_engine.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

namespace lab {

namespace act = wbi::actuation;

DelayedBackend::DelayedBackend(std::unique_ptr<act::SimulationBackend> inner, int delay_ticks,
                               std::string robot)
    : inner_(std::move(inner)), delay_ticks_(delay_ticks), robot_(std::move(robot)) {}

act::BackendDescription DelayedBackend::on_configure() {
  inner_->configure();
  line_.assign(static_cast<std::size_t>(delay_ticks_) + 1, act::JointCommands{});
  for (auto& command : line_) {
    command.resize(inner_->description().n_joints());
  }
  clear_line();
  const double period_ms = std::chrono::duration<double, std::milli>(inner_->step_period()).count();
  std::printf("lab_delayed: robot '%s': joint commands delayed by %d ticks (%.3g ms)\n",
              robot_.c_str(), delay_ticks_, delay_ticks_ * period_ms);
  std::fflush(stdout);
  return inner_->description();
}

void DelayedBackend::clear_line() {
  for (auto& command : line_) {
    command.set_idle();
    command.stamp = act::Time{0};
  }
  newest_ = 0;
}

void DelayedBackend::on_activate() { inner_->activate(); }

void DelayedBackend::on_deactivate() {
  inner_->deactivate();
  clear_line();  // a later activation does not replay this one's commands
}

void DelayedBackend::on_cleanup() { inner_->cleanup(); }

void DelayedBackend::on_shutdown() { inner_->shutdown(); }

void DelayedBackend::on_read(act::Time time, act::Duration period, act::SensorReadings& out) {
  inner_->read(time, period);
  out = inner_->readings();  // same sizes: copies values, allocates nothing
}

void DelayedBackend::on_write(act::Time time, act::Duration period, const act::JointCommands& in) {
  line_[newest_] = in;  // same sizes: no allocation
  newest_ = (newest_ + 1) % line_.size();
  // The oldest in the line, written delay_ticks_ writes ago, is due now.
  inner_->commands() = line_[newest_];
  inner_->write(time, period);
}

void DelayedBackend::on_step() { inner_->step(); }

std::unique_ptr<act::SimulationBackend> make_delayed_engine(
    const wbi::sim_robot::EngineRegistry& engines, const wbi::sim_robot::EngineContext& context) {
  constexpr int kMaxDelayTicks = 1000;
  const int delay_ticks = context.parameters.require<int>("delay_ticks");
  if (delay_ticks < 0 || delay_ticks > kMaxDelayTicks) {
    throw wbi::runtime::ParameterError(
        context.parameters.where("delay_ticks") + ": delay_ticks must be in [0, " +
        std::to_string(kMaxDelayTicks) + "], got " + std::to_string(delay_ticks));
  }
  return std::make_unique<DelayedBackend>(engines.create("wbi", context), delay_ticks,
                                          context.robot);
}

}  // namespace lab
