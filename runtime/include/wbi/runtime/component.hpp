// The component interface: a managed lifecycle (as ROS 2 managed nodes) and a
// periodic read → update → write cycle, run by a ComponentRunner (runner.hpp).
//
// States and what each allows:
//   UNCONFIGURED  created; no communication, no resources.
//   INACTIVE      configured (on_configure): parameters read, DDS endpoints
//                 created, buffers sized; reading allowed, no commands sent,
//                 no periodic cycle.
//   ACTIVE        running (on_activate): the periodic cycle runs at the
//                 configured rate; commands are sent/accepted.
//   FINALIZED     shut down (on_shutdown); ready to be destroyed.
// Transitions: configure (UNCONFIGURED → INACTIVE), activate (INACTIVE →
// ACTIVE), deactivate (ACTIVE → INACTIVE), cleanup (INACTIVE → UNCONFIGURED),
// shutdown (any → FINALIZED). A hook that throws leaves the state unchanged
// (shutdown excepted) and becomes the component's last error.
//
// The cycle runs on the runner's loop thread (or on the thread that delivers
// an event, cycles_on_event_thread()), only while ACTIVE:
//   read(t, period) → update(t, period) → write(t, period)
// update() must be real-time safe: no heap allocation, no blocking on DDS
// (use Subscriber::latest_into, Publisher::publish, Client::send/poll), no
// locks held by other threads for long. Size every buffer in on_configure.
#pragma once

#include <cstdint>
#include <string>

#include <wbi/vocabulary/lifecycle_state.hpp>

#include "wbi/runtime/clock.hpp"
#include "wbi/runtime/event_log.hpp"
#include "wbi/runtime/parameters.hpp"
#include "wbi/runtime/status_report.hpp"

namespace wbi::dds {
class Participant;
}

namespace wbi::runtime {

// States: wbi::LifecycleState (wbi/vocabulary/lifecycle_state.hpp), ROS 2's.

// What a component is given when it is configured.
struct ComponentContext {
  std::string instance;           // unique name in the deploy, e.g. "model"
  std::string type;               // registered type, e.g. "model_service"
  dds::Participant* participant;  // the process's participant
  Clock* clock;                   // the time of the periodic cycle and of stamps
};

// What an event's delivering thread calls to run the component's cycle
// (Component::cycles_on_event_thread).
class EventCycle {
 public:
  // Runs read → update → write on the calling thread when the component is
  // ACTIVE and event_ready(), again while it stays so (a few at most);
  // returns whether it ran. Waits for a cycle in progress on another thread
  // first; called from within the component's own cycle (an arrival nested
  // in its writes), returns false at once, and that cycle's end answers it.
  // Never throws.
  virtual bool run() = 0;

 protected:
  ~EventCycle() = default;
};

class Component {
 public:
  virtual ~Component() = default;
  Component(const Component&) = delete;
  Component& operator=(const Component&) = delete;

  // UNCONFIGURED → INACTIVE. Reads parameters (every key the component knows:
  // unknown keys are then rejected), creates endpoints, sizes buffers.
  virtual void on_configure(const Parameters& parameters, const ComponentContext& context) = 0;
  // INACTIVE → ACTIVE.
  virtual void on_activate() {}
  // ACTIVE → INACTIVE.
  virtual void on_deactivate() {}
  // INACTIVE → UNCONFIGURED: release what on_configure made.
  virtual void on_cleanup() {}
  // any → FINALIZED.
  virtual void on_shutdown() {}

  // The periodic cycle (ACTIVE only). time_ns: the clock's time at the start of
  // the cycle; period_ns: the nominal period.
  virtual void read(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) {}
  virtual void update(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) {}
  virtual void write(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) {}

  // Event-driven components (e.g. a controller that answers each new state
  // estimate at once) return true: the runner then starts a cycle whenever
  // wait_for_event() returns true instead of on the clock's ticks, and a cycle
  // misses its deadline when it ends more than one period after its event.
  virtual bool event_driven() const { return false; }
  // Blocks until the next event, at most timeout_ns; true when the event came.
  virtual bool wait_for_event(std::int64_t /*timeout_ns*/) { return true; }

  // An event-driven component whose events arrive on threads it does not own
  // (DDS listeners) can have its cycle run on the thread that delivers each
  // event, with no hand-off to the loop thread: it returns true here, and,
  // from the runner's set_event_cycle(cycle) on, calls cycle->run() on that
  // thread after each arrival that may complete an event. run() then starts a
  // cycle when event_ready() says one is due (never while another runs, nor
  // outside ACTIVE). The loop thread stays as a watchdog: it runs the cycle
  // the old way (wait_for_event, on its own thread) when no event was run for
  // ten periods, e.g. one whose inputs never all came. Asked after configure.
  virtual bool cycles_on_event_thread() const { return false; }
  // cycle: the runner's, until set_event_cycle(nullptr), after which no
  // arrival may call it (the component waits for a call in progress).
  virtual void set_event_cycle(EventCycle* /*cycle*/) {}
  // Without blocking: whether a cycle is due now (called under the runner's
  // cycle lock, on any thread).
  virtual bool event_ready() { return false; }

  // Named counters and the last error, published by the runner in the
  // component's status (status_report.hpp). The runner also records its own
  // errors here (a failed transition, a cycle that threw).
  StatusReport& report() { return report_; }
  const StatusReport& report() const { return report_; }

  // Faults and state changes, published by the runner on wbi/events with the
  // instance as their source (event_log.hpp; any thread, never blocks). The
  // runner adds the lifecycle's own; the robot named by the `robot`
  // parameter is the default robot.
  EventLog& events() { return events_; }

 protected:
  Component() = default;

 private:
  StatusReport report_;
  EventLog events_;
};

}  // namespace wbi::runtime
