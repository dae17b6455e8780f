// The controller contract: what the controller host (controllers/host) runs.
// No DDS here: a controller sees the robot only through the whole-body
// interface, and its parameters only through its ParameterTable.
//
// Lifecycle (as ros2_control's controllers; the host drives it):
//   declared    parameters(), references() and signal_names(): what it
//               takes and shows.
//   configure   INACTIVE: sizes its buffers for robot.dofs(), reads its
//               parameters. May allocate, may throw wbi::Error (the host then
//               refuses to run it, naming why).
//   activate    INACTIVE → ACTIVE, at a tick boundary, on the loop thread:
//               `measured` is the state of that tick; sets its control mode
//               (on the joints it commands: the host's interface applies a
//               mode to those only).
//   update      ACTIVE, once per tick: reads the state and computes
//               command(); returns false when there is nothing new to send
//               (e.g. that state was answered already). The host sends the
//               command: after a switch it adds the difference between the
//               last command sent and this controller's first, decaying, so
//               that no controller jumps (bumpless). Real-time: no
//               allocation, no blocking. A StaleDataError skips the tick (no
//               command; the robot's watchdog guards); any other exception
//               makes the host fall back to `hold` and say why.
//   deactivate  ACTIVE → INACTIVE, at a tick boundary; sends nothing.
// A parameter change reaches an active controller between two ticks:
// parameters_changed() then re-reads what it uses (real-time as update).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <wbi/registry.hpp>

#include "wbi/controllers/parameter_table.hpp"
#include "wbi/controllers/reference_input.hpp"
#include "wbi/controllers/reference_output.hpp"
#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers {

class Controller {
 public:
  virtual ~Controller() = default;
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  virtual std::vector<ParameterSpec> parameters() const = 0;
  // What signals() carries, in order (published on wbi/<robot>/signals/<host>).
  virtual std::vector<std::string> signal_names() const { return {}; }
  // Its reference inputs (reference_input.hpp), each a topic
  // wbi/<robot>/references/<controller>/<input>.
  virtual std::vector<ReferenceSpec> references() const { return {}; }
  // Before configure: the host's inputs, one per references() entry, in
  // order. They live as long as the controller.
  virtual void bind_references(std::span<ReferenceInput* const> /*inputs*/) {}
  // Its reference outputs (reference_output.hpp): a planner's points, written
  // in update() into the input of another controller of the same host that
  // the deploy file chains to it (that controller updates after it, in the
  // same tick). Bound before configure, one per outputs() entry, in order.
  virtual std::vector<ReferenceSpec> outputs() const { return {}; }
  virtual void bind_outputs(std::span<ReferenceOutput* const> /*outputs*/) {}
  // The joints it commands, unless the deploy file names them (`joints:` in
  // its entry): true, all of the host's; false, none (a planner, whose work
  // is its outputs). Active controllers command disjoint joints; the host's
  // joints that none commands are held by `hold`.
  virtual bool commands_joints() const { return true; }
  // Before configure: the joints it commands (indices into robot.joint_list()),
  // for a controller that reports on them alone (its error figures).
  virtual void bind_joints(std::span<const int> /*joints*/) {}

  virtual void configure(WholeBodyInterface& robot, const ParameterTable& parameters) = 0;
  virtual void activate(const RobotState& measured) = 0;
  // time_s: the robot's time since the host's first tick; period_s: the nominal period.
  virtual bool update(double time_s, double period_s) = 0;
  virtual void deactivate() {}
  virtual void parameters_changed(const ParameterTable& /*parameters*/) {}
  // A new estimator took over the state stream: its world frame need not be
  // the old one's (loop thread, before the next update).
  virtual void state_source_changed() {}
  // True when the controller's run is over (e.g. an experiment of fixed
  // length): the host then ends its process.
  virtual bool finished() const { return false; }

  // The joint torques (or references, in the mode activate() set) of the last
  // update(), one per host joint: the host sends the entries of the joints
  // it commands.
  virtual const Eigen::VectorXd& command() const = 0;
  // Values of signal_names() at the last update(), and the source stamp of the
  // state they come from (the host publishes them once per new stamp).
  virtual std::span<const double> signals() const { return {}; }
  virtual std::int64_t signals_stamp_ns() const { return 0; }
  // One line of progress, e.g. "max joint error 0.0012 rad" (no allocation).
  virtual void progress(char* line, std::size_t size) const {
    if (size > 0) {
      line[0] = '\0';
    }
  }
  // Printed when the host shuts down, e.g. "final max joint error: 0.0006 rad".
  virtual std::string summary() const { return {}; }
  // Empty when summary()'s figures are computed over what they claim; else
  // why they are not, e.g. "no CoM reference point came". Asked when the run
  // ends (finished() or the host's exit_after_s): a non-empty answer fails it
  // (the process exits with runtime::kExitRunFailed, `wbi launch` with 1).
  virtual std::string figures_missing() const { return {}; }

 protected:
  Controller() = default;
};

// Controller types by name. A plugin (wbi/plugin.hpp) registers its
// controllers here, one add<C>(type, description) each.
class ControllerRegistry : public wbi::Registry<Controller> {
 public:
  static constexpr const char* kKind = "controller type";  // its name in a wbi::Catalog
  ControllerRegistry() : wbi::Registry<Controller>("controller type") {}
  using wbi::Registry<Controller>::add;
  template <class C>
  void add(const std::string& type, std::string description = "") {
    add(
        type, [] { return std::make_unique<C>(); }, std::move(description));
  }
};

}  // namespace wbi::controllers
