// The controller host: runs the controllers of one robot's joints through one
// whole-body interface and drives their lifecycle (controller.hpp). No DDS
// here: the component (controller_host_component.cpp) gives it the interface
// and answers requests.
//
// Joint sets. Each controller commands a set of the host's joints (all of
// them unless set_joints() names others; none for a planner). Any number of
// controllers are active at once on disjoint sets; the joints no active
// controller commands are held by `hold`, the host's own controller
// (make_hold_controller: gravity compensation and joint damping about the
// posture measured when it takes them). Every controller reads the whole
// state and model; its Actuators reach only its own joints.
//
// Chaining. A planner's reference output can feed a controller's reference
// input in the same tick (chain()): the planner updates first, without DDS
// and without a tick of delay, and is active exactly while a controller it
// feeds is.
//
// Threads. tick() runs on the loop thread. request_switch() and
// set_parameter() may be called from any thread: they check the request at
// once (a refusal changes nothing and says why in one line) and hand an
// accepted one to the loop, which applies it between two ticks, whole.
//
// Sending. Each tick the host composes one command from its active
// controllers' command() (each on its own joints, hold on the rest) and
// sends it once, when every active controller had something new. After a
// switch or a fallback it adds, on the joints that changed hands, the
// difference between the last command sent and the new controller's first,
// decaying with the time constant `blend_s`: the first command continues
// the last, and the new law takes over smoothly (bumpless transfer),
// whatever the controller; the other joints see nothing of the switch.
//
// Fallback. When a controller throws in update() or overruns its period
// `overrun_limit` ticks in a row, it is deactivated and hold takes its
// joints (only those). Not on a StaleDataError (no fresh state: the tick is
// skipped, counter "stale_cycles") nor on a TimeoutError (a service it
// needs, e.g. a remote model, is late: skipped, counter "late_services"):
// hold would lack the same. Each fallback is counted (status counter
// "fallbacks"), becomes the status's last error with its reason, and is
// printed on stderr: never a silent stop.
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
#include <span>
#include <string>
#include <vector>

#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/status_report.hpp>

#include "wbi/controllers/controller.hpp"

namespace wbi::controllers {

inline constexpr const char* kHoldController = "hold";
// The host's own fallback (src/hold_controller.hpp): gravity compensation and
// joint damping about the posture measured at its activation.
std::unique_ptr<Controller> make_hold_controller();

struct ControllerInfo {
  std::string name, type;
  bool active = false;
  std::string configure_error;  // empty when configured
};

struct SwitchResult {
  bool done = false;
  std::string from, to;      // the controllers deactivated and activated ("none"; "hold"
                             // when it gives or takes joints)
  std::string text;          // the refusal, or what happened ("pd → hold at t = 2.000 s …")
  double torque_step = 0.0;  // ‖τ_after − τ_before‖ / ‖τ_before‖ at the switch tick
  // The same over the joints that changed hands, and over the others (which
  // a switch of another joint set must leave alone: 0 when it does).
  double torque_step_switched = 0.0, torque_step_others = 0.0;
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

struct PinnedState;  // src/joint_set_interface.hpp

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
  // The joints `name` commands, by name, among the host's (before its
  // configure). Without it: all of them, or none when the controller's
  // commands_joints() is false. Throws wbi::Error naming an unknown or
  // repeated joint.
  void set_joints(const std::string& name, const std::vector<std::string>& joints);
  // Feeds `downstream`'s reference input `input` from `upstream`'s reference
  // output `output` in the same tick (reference_output.hpp); no topic is then
  // read for that input. Throws wbi::Error naming what does not exist, a size
  // mismatch, an input chained twice or a cycle.
  void chain(const std::string& downstream, const std::string& input, const std::string& upstream,
             const std::string& output);
  // Configures `name`. A failure is kept (the controller cannot be activated;
  // list() shows why) and rethrown as wbi::Error naming the controller.
  void configure(const std::string& name);
  // The controllers active from the first tick (their joints disjoint; the
  // rest held; `hold` alone: all held). Throws wbi::Error naming the problem.
  void set_initial(const std::vector<std::string>& names);
  void set_initial(const std::string& name) { set_initial(std::vector<std::string>{name}); }

  // Loop thread, once per tick: applies a pending switch and parameter
  // changes, then runs the active controllers and sends the command.
  // time_s: the robot's time (the host's component uses the state's stamps,
  // so that a lockstep run does not depend on the wall clock). Allocates
  // nothing (a switch or fallback runs activate(), which may).
  void tick(double time_s, double period_s);
  // Loop thread: stages a switch to `activate` for this tick, without
  // waiting: it takes its joints from the active controllers that command
  // them ("hold": every active controller's joints go to hold). "" when
  // staged, else the refusal.
  // from: the controller whose joints it takes instead (activate "hold":
  // hold takes from's joints).
  std::string schedule_switch(const std::string& activate, const std::string& from = "");
  // Loop thread: the result of the last switch that ended, and how many have;
  // the same once its blend is over (largest_change), and how many have.
  const SwitchResult& last_switch() const { return last_switch_; }
  std::uint64_t switches_ended() const { return switches_done_; }
  const SwitchResult& last_settled() const { return settling_; }
  std::uint64_t switches_settled() const { return switches_settled_; }
  // The command sent at the last tick.
  const Eigen::VectorXd& last_command() const { return last_command_; }
  // The active controllers' names in update order, then "hold" when it holds
  // joints ("pd", "balance, arms", "balance, hold"); "" before the first tick.
  std::string active() const;
  // The first active controller on joints (hold when it alone holds them), or
  // null: the one whose progress and signals the host's component shows.
  Controller* active_controller();
  // Every active controller, hold last when it holds joints (loop thread).
  std::span<Controller* const> active_controllers() const { return running_controllers_; }

  // Any thread.
  // A new estimator took over the state stream: told to the active controllers
  // before their next update.
  void notify_state_source_changed() { state_source_changed_.store(true); }
  // Activates and deactivates any number of controllers at one tick boundary,
  // whole or not at all: joints of the deactivated that no activated one
  // takes go to hold; naming `hold` to activate says just that. Refused with
  // one line when a name is unknown, a controller cannot be activated, is
  // (not) active, or two active controllers would command the same joint.
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

  // Setup: a controller's reference inputs fed from their topics (those not chained).
  std::vector<ReferenceInput*> references(const std::string& controller) const;
  // Lockstep runs whose references come from generators in step with the
  // robot: each reference input waits at most wait_ns for its point
  // (ReferenceInput::set_wait; late points counted, "late_references").
  // Setup, before the loop. Chained inputs never wait: their points come first.
  void set_reference_wait(std::int64_t wait_ns);
  // Loop thread, before the first tick: waits for every hosted controller's
  // topic-fed inputs' first point for time_ns (the state's source stamp), so
  // that the generators start at the host's first state. False when one was late.
  bool wait_for_first_references(std::int64_t time_ns);
  // Without waiting: whether a tick at time_ns would find every waited-for
  // reference in (first: the host's first tick, which waits for each one's
  // first point; ReferenceInput::ready_for). True when none is waited for.
  bool references_ready(std::int64_t time_ns, bool first) const;

  // The summaries of every controller that ran, and its references' counts, for shutdown.
  std::string summary() const;

 private:
  struct Hosted;
  struct PendingSwitch {
    bool pending = false;
    std::vector<Hosted*> activate, deactivate;  // closed over the chains; hold not in them
    SwitchResult result;
  };

  Hosted& find(const std::string& name) const;
  // The switch that does what was asked, with the chains' planners added or
  // removed; its result's text is the refusal when it cannot be done.
  PendingSwitch plan_switch(const std::vector<Hosted*>& activate,
                            const std::vector<Hosted*>& deactivate, bool to_hold) const;
  std::string check_joints(const std::vector<Hosted*>& after,
                           const std::vector<Hosted*>& deactivate) const;
  // Loop thread. Activates `hosted` from the measured state (false: no fresh
  // state yet); its joints become its own.
  bool activate(Hosted& hosted);
  void deactivate(Hosted& hosted);
  // Hold (re)takes the joints no controller commands, from the measured posture.
  void take_free_joints_to_hold();
  void give_joints(const Hosted& hosted, Hosted* owner);  // blend where they change hands
  bool start(double time_s);                              // the initial controllers
  bool apply_switch(double time_s);                       // false: not this tick
  void finish_switch();
  void wake_parameter_waiters();
  void fall_back(Hosted& hosted, const std::string& reason, double time_s);
  // Runs one controller's update; its command on its joints. 1 fresh, 0 nothing new, -1 it failed.
  int run(Hosted& hosted, double time_s, double period_s, bool source_changed);
  void send(double time_s);
  void report_references(Hosted& hosted, double time_s);  // its stale episodes
  void count_references();                                // the status counters
  // Whether it runs this tick (hold: while it holds joints). Changed under switch_mutex_.
  bool is_running(const Hosted& hosted) const;
  void rebuild_running();  // running_ and running_controllers_ from active_ (at a change)

  WholeBodyInterface& robot_;
  runtime::StatusReport& report_;
  runtime::EventLog& events_;
  Options options_;
  std::vector<std::unique_ptr<Hosted>> hosted_;
  Hosted* hold_ = nullptr;
  std::vector<Hosted*> initial_;  // activated by the first tick (with a fresh state)
  bool started_ = false;
  bool hold_active_ = false;         // hold commands the joints owner_ leaves free
  bool hold_pending_ = false;        // hold should take joints: tried again each tick
  std::vector<Hosted*> active_;      // active controllers but hold, upstream first
  std::vector<Hosted*> running_;     // active_ then hold when active: this tick's updates
  std::vector<Hosted*> tick_order_;  // running_ as the tick began
  std::vector<Controller*> running_controllers_;
  std::vector<Hosted*> owner_;  // per joint: the active controller commanding it; null: free
  RobotState measured_;         // read at an activation
  // With chains, the state each tick began with, which every controller reads
  // (src/joint_set_interface.hpp); pin_state_: there is a chain.
  std::unique_ptr<PinnedState> pinned_;
  bool pin_state_ = false;
  Eigen::VectorXd command_;        // composed from the controllers' commands this tick
  Eigen::VectorXd last_command_;   // the last command sent
  Eigen::VectorXd before_switch_;  // last_command_ when a switch began
  // Per joint: the old command's part at blend_start_s_[j]; pending: set at
  // the next send; blending: still decaying.
  Eigen::VectorXd blend_, blend_start_s_;
  std::vector<char> blend_pending_, blending_, switched_;
  int blending_joints_ = 0;
  SwitchResult last_switch_;
  SwitchResult settling_;         // the last switch, while its blend is watched
  double settle_until_s_ = -1.0;  // < 0: not watching
  double largest_change_ = 0.0;   // between two commands sent, since the last switch [N m]
  std::uint64_t switches_settled_ = 0;
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
  PendingSwitch switch_;
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
