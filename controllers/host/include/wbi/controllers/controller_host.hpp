// The controller host: runs the controllers of one robot's joints through one
// whole-body interface, one controller active at a time, and drives their
// lifecycle (controller.hpp). No DDS here: the component
// (controller_host_component.cpp) gives it the interface and answers requests.
//
// Threads. tick() runs on the loop thread. request_switch() and
// set_parameter() may be called from any thread: they check the request at
// once (a refusal changes nothing and says why in one line) and hand an
// accepted one to the loop, which applies it between two ticks, whole.
//
// Sending. The host sends the active controller's command(). After a switch
// or a fallback it adds the difference between the last command sent and the
// new controller's first, decaying with the time constant `blend_s`: the
// first command continues the last, and the new law takes over smoothly
// (bumpless transfer), whatever the controller.
//
// Fallback. The built-in `hold` controller (gravity compensation and joint
// damping about the measured posture) takes over when the active controller
// throws in update() or overruns its period `overrun_limit` ticks in a row.
// Not on a StaleDataError (no fresh state: the tick is skipped, counter
// "stale_cycles") nor on a TimeoutError (a service it needs, e.g. a remote
// model, is late: skipped, counter "late_services"): hold would lack the same.
// Each fallback is counted (status counter "fallbacks"), becomes the status's
// last error with its reason, and is printed on stderr: never a silent stop.
//
// Events (wbi/events, the component's EventLog): CONTROLLER_FALLBACK (warning,
// the fallback's line), CONTROLLER_SWITCHED (info, what the switch did),
// PARAMETER_CHANGED (info, the value staged) and REFERENCE_STALE (warning,
// once per episode of a reference input).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/status_report.hpp>

#include "wbi/controllers/controller.hpp"

namespace wbi::controllers {

inline constexpr const char* kHoldController = "hold";

struct ControllerInfo {
  std::string name, type;
  bool active = false;
  std::string configure_error;  // empty when configured
};

struct SwitchResult {
  bool done = false;
  std::string from, to;        // the controllers deactivated and activated ("none")
  std::string text;            // the refusal, or what happened ("pd → hold at t = 2.000 s …")
  double torque_step = 0.0;    // ‖τ_after − τ_before‖ / ‖τ_before‖ at the switch tick
  double time_s = 0.0;         // when it took effect
  double torque_before = 0.0;  // ‖τ‖ of the last command before the switch [N m]
  // Once the blend is over (5 blend_s after the switch): the largest change
  // between two consecutive commands in that time, / torque_before. The
  // torque step above is 0 by construction; this says how smooth the take-over was.
  double largest_change = 0.0;
  // The same from the previous switch (or the start) to this one: the
  // controllers' own tick-to-tick change, which the take-over is compared with.
  double largest_change_before = 0.0;
  double settled_after_s = 0.0;
};

class ControllerHost {
 public:
  struct Options {
    // Consecutive ticks whose update() took longer than the period before the
    // fallback; 0: never. Off by default: in lockstep a tick's wall time is not
    // its deadline, and a remote model's call may take longer than a period
    // by design. A real-time deploy sets it (e.g. 10).
    int overrun_limit = 0;
    double blend_s = 0.1;  // after a switch, the old command's part decays so (0: none)
    std::chrono::milliseconds switch_timeout{2000};  // request_switch waits this long for the loop
  };

  // robot: initialized, with the host's joints. report: counters and last
  // error; events: its faults and changes (both the component's).
  ControllerHost(WholeBodyInterface& robot, runtime::StatusReport& report,
                 runtime::EventLog& events, Options options);
  ~ControllerHost();
  ControllerHost(const ControllerHost&) = delete;
  ControllerHost& operator=(const ControllerHost&) = delete;

  // Setup, before the loop. Adds a controller and returns its parameter table
  // (sized, with defaults) for the caller to set values; then configure(name).
  // Throws wbi::Error for a name taken.
  ParameterTable& add(const std::string& name, const std::string& type,
                      std::unique_ptr<Controller> controller);
  // Configures `name`. A failure is kept (the controller cannot be activated;
  // list() shows why) and rethrown as wbi::Error naming the controller.
  void configure(const std::string& name);
  // The controller active from the first tick (reads the state then).
  void set_initial(const std::string& name);

  // Loop thread, once per tick: applies a pending switch and parameter
  // changes, then runs the active controller and sends its command.
  // time_s: the robot's time (the host's component uses the state's stamps,
  // so that a lockstep run does not depend on the wall clock). Allocates
  // nothing (a switch or fallback runs activate(), which may).
  void tick(double time_s, double period_s);
  // Loop thread: stages a switch to `activate` (from the active controller)
  // for this tick, without waiting. "" when staged, else the refusal.
  std::string schedule_switch(const std::string& activate);
  // Loop thread: the result of the last switch that ended, and how many have;
  // the same once its blend is over (largest_change), and how many have.
  const SwitchResult& last_switch() const { return last_switch_; }
  std::uint64_t switches_ended() const { return switches_done_; }
  const SwitchResult& last_settled() const { return settling_; }
  std::uint64_t switches_settled() const { return switches_settled_; }
  // The command sent at the last tick.
  const Eigen::VectorXd& last_command() const { return last_command_; }
  // The active controller's name, "" before the first tick.
  const std::string& active() const;
  Controller* active_controller();

  // Any thread.
  // A new estimator took over the state stream: told to the active controller
  // before its next update.
  void notify_state_source_changed() { state_source_changed_.store(true); }
  SwitchResult request_switch(const std::vector<std::string>& activate,
                              const std::vector<std::string>& deactivate);
  // Throws wbi::Error with one line naming the controller, parameter, value and range.
  void set_parameter(const std::string& controller, const std::string& parameter,
                     const std::vector<double>& values);
  // Waits until the loop applied a staged change of `controller`'s parameters:
  // its table's generation() is past `generation` (read before staging), at
  // most `timeout`. True when it is. Woken by the tick that applies it.
  bool wait_for_parameters(const std::string& controller, std::uint64_t generation,
                           std::chrono::nanoseconds timeout) const;
  const ParameterTable& parameters(const std::string& controller) const;
  std::vector<ControllerInfo> list() const;

  // Setup: a controller's reference inputs (to feed from their topics).
  std::vector<ReferenceInput*> references(const std::string& controller) const;
  // Lockstep runs whose references come from generators in step with the
  // robot: each reference input waits at most wait_ns for its point
  // (ReferenceInput::set_wait; late points counted, "late_references").
  // Setup, before the loop.
  void set_reference_wait(std::int64_t wait_ns);
  // Loop thread, before the first tick: waits for every hosted controller's
  // inputs' first point for time_ns (the state's source stamp), so that the
  // generators start at the host's first state. False when one was late.
  bool wait_for_first_references(std::int64_t time_ns);

  // The summaries of every controller that ran, and its references' counts, for shutdown.
  std::string summary() const;

 private:
  struct Hosted;
  Hosted& find(const std::string& name) const;
  // first_start: nothing was commanded before (no blend from a last command).
  bool activate(Hosted& hosted, bool first_start);
  void deactivate(Hosted& hosted);
  bool apply_switch(double time_s);  // false: not this tick
  void finish_switch();
  void wake_parameter_waiters();
  void fall_back(const std::string& reason, double time_s);
  void run_active(double time_s, double period_s);
  void send(double time_s);
  void report_references(Hosted& active, double time_s);
  SwitchResult check_switch(Hosted* to, Hosted* from) const;  // result.text: the refusal

  WholeBodyInterface& robot_;
  runtime::StatusReport& report_;
  runtime::EventLog& events_;
  Options options_;
  std::vector<std::unique_ptr<Hosted>> hosted_;
  Hosted* active_ = nullptr;
  Hosted* initial_ = nullptr;
  RobotState measured_;            // read at an activation
  Eigen::VectorXd last_command_;   // the last command sent
  Eigen::VectorXd before_switch_;  // last_command_ when a switch began
  Eigen::VectorXd blend_;          // the old command's part, at blend_start_s_
  bool blend_pending_ = false, blending_ = false;
  double blend_start_s_ = 0.0;
  SwitchResult last_switch_;
  SwitchResult settling_;         // the last switch, while its blend is watched
  double settle_until_s_ = -1.0;  // < 0: not watching
  double largest_change_ = 0.0;   // between two commands sent, since the last switch [N m]
  std::uint64_t switches_settled_ = 0;
  int overruns_in_a_row_ = 0;
  std::int64_t reference_wait_ns_ = 0;
  std::atomic<bool> state_source_changed_{false};
  // Parameter changes applied this tick (or a wake-up deferred from an earlier
  // tick): the waiters of wait_for_parameters() are woken.
  bool parameters_applied_ = false;
  runtime::StatusCounter *switches_, *refused_, *fallbacks_, *stale_, *late_, *overruns_, *changes_,
      *late_references_, *stale_references_;

  // A switch handed from request_switch() to the loop.
  mutable std::mutex switch_mutex_;
  std::condition_variable switch_done_;
  struct PendingSwitch {
    bool pending = false;
    Hosted* activate = nullptr;    // null: none
    Hosted* deactivate = nullptr;  // null: none
    SwitchResult result;
  } switch_;
  std::atomic<bool> switch_requested_{
      false};  // switch_.pending, for the loop's check without the lock
  std::uint64_t switches_done_ = 0;

  // wait_for_parameters() sleeps on this; the loop only tries the lock and
  // notifies (a waiter between its check and its wait holds the lock: woken
  // at the next tick instead).
  mutable std::mutex applied_mutex_;
  mutable std::condition_variable applied_;
};

}  // namespace wbi::controllers
