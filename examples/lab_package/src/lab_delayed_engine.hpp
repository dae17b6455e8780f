// `lab_delayed`: wbi's own simulation engine ("wbi") with the lab robot's
// transmission delay: the joint commands written at tick k reach the plant
// at tick k + N, as on a real robot whose commands cross a bus before its
// motor drivers apply them. Sensors are not delayed.
//
// N is the sim_robot component's parameter `delay_ticks` (required, 0 to
// 1000); the engine reads it from EngineContext::parameters, so that a deploy
// file gives it beside `engine: lab_delayed`. Every other key is the inner
// engine's (config, pushes, …).
//
// DelayedBackend wraps any SimulationBackend and drives its public lifecycle
// from its own hooks (wbi/actuation/robot_backend.hpp):
//   on_configure   inner.configure(); the delay line sized and IDLE; the
//                  inner description is this backend's
//   on_activate    inner.activate()        on_deactivate  inner.deactivate()
//   on_cleanup     inner.cleanup()         on_shutdown    inner.shutdown()
//   on_read        inner.read(); its readings copied
//   on_write       the command enters the line; the one N writes old is
//                  given to inner.write() (IDLE for the first N)
//   on_step        inner.step()
// Time, period and ground truth are the inner engine's. Nothing allocates
// after configure.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <wbi/sim_robot/engine_registry.hpp>

namespace lab {

class DelayedBackend final : public wbi::actuation::SimulationBackend {
 public:
  // robot: its name in the deploy file (for the line said at configure).
  DelayedBackend(std::unique_ptr<wbi::actuation::SimulationBackend> inner, int delay_ticks,
                 std::string robot);

  wbi::actuation::Duration step_period() const override { return inner_->step_period(); }
  double time() const override { return inner_->time(); }
  wbi::actuation::Time stamp() const override { return inner_->stamp(); }
  const wbi::actuation::GroundTruth& ground_truth() const override {
    return inner_->ground_truth();
  }

 protected:
  wbi::actuation::BackendDescription on_configure() override;
  void on_activate() override;
  void on_deactivate() override;
  void on_cleanup() override;
  void on_shutdown() override;
  void on_read(wbi::actuation::Time time, wbi::actuation::Duration period,
               wbi::actuation::SensorReadings& out) override;
  void on_write(wbi::actuation::Time time, wbi::actuation::Duration period,
                const wbi::actuation::JointCommands& in) override;
  void on_step() override;

 private:
  void clear_line();  // every command in the line IDLE

  std::unique_ptr<wbi::actuation::SimulationBackend> inner_;
  const int delay_ticks_;
  const std::string robot_;
  std::vector<wbi::actuation::JointCommands> line_;  // ring of delay_ticks_ + 1 commands
  std::size_t newest_ = 0;                           // the slot the next write fills
};

// The engine's factory: the "wbi" engine of `engines` (the catalog's: the
// plugin keeps a pointer to it), wrapped.
std::unique_ptr<wbi::actuation::SimulationBackend> make_delayed_engine(
    const wbi::sim_robot::EngineRegistry& engines, const wbi::sim_robot::EngineContext& context);

}  // namespace lab
