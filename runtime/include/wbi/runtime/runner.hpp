// ComponentRunner: owns one component, drives its lifecycle, runs its periodic
// cycle on a loop thread at a given rate on a Clock, measures the loop's timing
// and publishes the component's status on wbi/status (from its own thread,
// so the cycle never waits on DDS), with the counters and last error of the
// component's StatusReport (status_report.hpp), and its events on wbi/events
// (event_log.hpp), with one of its own at each transition and failure.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "wbi/runtime/component.hpp"
#include "wbi/runtime/duration_histogram.hpp"
#include "wbi/runtime/event_pump.hpp"

namespace wbi::runtime {

// A transition that is not allowed from the current state, or whose hook failed.
class TransitionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// configure failed on the component's parameters or inputs (its on_configure
// threw ParameterError or std::invalid_argument: a bad value, an unknown
// joint, a missing file): starting the process again cannot fix it.
class ConfigurationError : public TransitionError {
 public:
  using TransitionError::TransitionError;
};

struct RunnerOptions {
  double rate_hz = 0.0;          // periodic cycle rate; 0: no cycle (event-driven component)
  double status_period_s = 1.0;  // heartbeat period on wbi/status; 0: on transitions only
};

// Timing of the periodic cycle since the last activation.
struct LoopStats {
  std::uint64_t iterations = 0;
  std::uint64_t overruns =
      0;  // cycles that ended after the next cycle's start (those ticks are skipped)
  std::uint64_t errors = 0;      // cycles whose read/update/write threw
  double period_mean_s = 0.0;    // measured start-to-start period
  double period_jitter_s = 0.0;  // its standard deviation
  double period_max_s = 0.0;
  double cycle_mean_s = 0.0;  // time spent in read + update + write
  double cycle_max_s = 0.0;
  // Cycles run on the thread that delivered their event
  // (Component::cycles_on_event_thread); the others ran on the loop thread.
  std::uint64_t on_event_thread = 0;
};

class ComponentRunner final : private EventCycle {
 public:
  // context.participant and context.clock must outlive the runner.
  ComponentRunner(std::unique_ptr<Component> component, ComponentContext context,
                  RunnerOptions options = {});
  ~ComponentRunner();  // shuts the component down if needed
  ComponentRunner(const ComponentRunner&) = delete;
  ComponentRunner& operator=(const ComponentRunner&) = delete;

  // Transitions. Throw TransitionError naming the component when not allowed
  // from the current state or when the hook throws (state then unchanged).
  void configure(const Parameters& parameters);
  void activate();
  void deactivate();
  void cleanup();
  void shutdown();  // from any state; always ends FINALIZED

  LifecycleState state() const { return state_.load(); }
  LoopStats stats() const;
  // The component's last error (its own report, or a failed transition or cycle).
  std::string last_error() const;
  const ComponentContext& context() const { return context_; }
  const RunnerOptions& options() const { return options_; }
  Component& component() { return *component_; }

  // Publishes the status now (also done every status_period_s and on transitions).
  void publish_status();

 private:
  void require(LifecycleState from, const char* transition) const;
  [[noreturn]] void fail(const char* transition, const std::exception& error,
                         bool configuration = false);
  void set_state(LifecycleState state);
  void lifecycle_event(EventSeverity severity, const std::string& text);
  void run_loop();
  // A component that cycles on its events' threads: the loop thread's watch.
  void run_watchdog();
  // One read → update → write now, on this thread, and its statistics.
  void run_cycle(bool event_driven, bool on_event_thread = false);
  bool run() override;  // EventCycle: an event's delivering thread
  // While the component says a cycle is due, runs one (cycle_mutex_ held).
  bool run_ready_cycles(bool on_event_thread);
  // run_cycle, marked as this thread's: an event nested in it waits for its end.
  void run_guarded_cycle(bool on_event_thread);
  // An event-driven component's wait, bounded so that a stop request is seen.
  bool wait_for_event(std::int64_t period_ns);
  void stop_loop();
  void print_cycle_times();
  void run_heartbeat();

  std::unique_ptr<Component> component_;
  ComponentContext context_;
  RunnerOptions options_;
  std::atomic<LifecycleState> state_{LifecycleState::unconfigured};

  mutable std::mutex mutex_;  // guards stats_ and cycle_times_
  LoopStats stats_;
  // Each cycle's read + update + write on the steady clock (the component's
  // clock may be simulated), for the line deactivate() prints.
  DurationHistogram cycle_times_;

  // The start-to-start period's running mean and variance (Welford), and
  // the periodic loop's next tick: whichever thread runs the cycle.
  std::int64_t last_start_ns_ = -1;
  std::int64_t next_ns_ = 0;
  double period_mean_s_ = 0.0, period_m2_ = 0.0;
  std::uint64_t periods_ = 0;

  std::atomic<bool> loop_stop_{false};
  std::thread loop_;

  // Cycles on events' threads (Component::cycles_on_event_thread): one at a
  // time, only while cycling_; the watchdog sleeps on watchdog_wake_.
  std::mutex cycle_mutex_;
  std::condition_variable watchdog_wake_;
  bool cycling_ = false;
  bool on_event_thread_ = false;  // transitions' threads only (the loop is given its mode)
  std::uint64_t cycles_run_ = 0;
  std::int64_t period_ns_ = 0;

  struct Status;
  std::unique_ptr<Status> status_;  // publisher and heartbeat thread
  std::unique_ptr<EventPump> events_;
};

}  // namespace wbi::runtime
