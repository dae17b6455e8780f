#include "wbi/runtime/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "wbi/runtime/console_line.hpp"

namespace wbi::runtime {

namespace {
// The report's counters and error into the sample; allocates only when a
// counter was added (configure). last_error is a bounded string: no allocation.
void copy_report(const StatusReport& report, msg::ComponentStatus& sample) {
  const std::size_t n = report.counter_count();
  auto& counters = sample.counters();
  if (counters.size() != n) {
    counters.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      counters[i].name(report.counter_name(i));
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    counters[i].value(report.counter_value(i));
  }
  report.last_error_into(sample.last_error());
}

}  // namespace

struct ComponentRunner::Status {
  dds::Publisher<msg::ComponentStatus> publisher;
  msg::ComponentStatus sample;
  std::mutex mutex;  // guards sample, stop, kicks
  std::condition_variable kicked;
  bool stop = false;
  std::uint64_t kicks = 0;
  std::thread thread;

  explicit Status(dds::Participant& participant)
      : publisher(participant, dds::topics::kStatus, dds::qos::kStatus) {}
};

ComponentRunner::ComponentRunner(std::unique_ptr<Component> component, ComponentContext context,
                                 RunnerOptions options)
    : component_(std::move(component)), context_(std::move(context)), options_(options) {
  if (!component_) {
    throw std::invalid_argument("component '" + context_.instance + "': no component");
  }
  if (context_.participant == nullptr || context_.clock == nullptr) {
    throw std::invalid_argument("component '" + context_.instance + "': no participant or clock");
  }
  if (!(options_.rate_hz >= 0.0) || !std::isfinite(options_.rate_hz)) {
    throw std::invalid_argument("component '" + context_.instance + "': rate_hz must be >= 0");
  }
  status_ = std::make_unique<Status>(*context_.participant);
  status_->sample.instance(context_.instance);
  status_->sample.type(context_.type);
  status_->sample.rate_hz(options_.rate_hz);
  status_->thread = std::thread([this] { run_heartbeat(); });
  events_ =
      std::make_unique<EventPump>(*context_.participant, component_->events(), context_.instance);
}

ComponentRunner::~ComponentRunner() {
  try {
    if (state() != LifecycleState::finalized) {
      shutdown();
    }
  } catch (...) {
    // already recorded as the last error
  }
  {
    std::lock_guard lock(status_->mutex);
    status_->stop = true;
  }
  status_->kicked.notify_all();
  status_->thread.join();
  events_.reset();  // sends the events still queued
}

void ComponentRunner::require(LifecycleState from, const char* transition) const {
  if (state() != from) {
    throw TransitionError("component '" + context_.instance + "': cannot " + transition + " from " +
                          to_string(state()) + " (only from " + to_string(from) + ")");
  }
}

void ComponentRunner::fail(const char* transition, const std::exception& error,
                           bool configuration) {
  const std::string text = "component '" + context_.instance + "' (" + context_.type +
                           "): " + transition + " failed: " + error.what();
  component_->report().set_error(error.what());
  lifecycle_event(EventSeverity::error, std::string(transition) + " failed: " + error.what());
  publish_status();
  if (configuration) {
    throw ConfigurationError(text);
  }
  throw TransitionError(text);
}

void ComponentRunner::set_state(LifecycleState state) {
  const LifecycleState from = state_.exchange(state);
  lifecycle_event(EventSeverity::info, std::string(to_string(from)) + " -> " + to_string(state));
  publish_status();
}

void ComponentRunner::lifecycle_event(EventSeverity severity, const std::string& text) {
  component_->events().emit(severity, EventKind::lifecycle, text);
}

void ComponentRunner::configure(const Parameters& parameters) {
  require(LifecycleState::unconfigured, "configure");
  try {
    component_->on_configure(parameters, context_);
    parameters.reject_unknown();
    if (parameters.has("robot")) {
      component_->events().set_default_robot(parameters.get<std::string>("robot", ""));
    }
  } catch (const std::exception& error) {
    const bool bad_parameter = dynamic_cast<const ParameterError*>(&error) != nullptr;
    if (bad_parameter) {
      try {
        component_->on_cleanup();  // undo what on_configure did before the bad key was found
      } catch (...) {
      }
    }
    fail("configure", error,
         bad_parameter || dynamic_cast<const std::invalid_argument*>(&error) != nullptr);
  }
  set_state(LifecycleState::inactive);
}

void ComponentRunner::activate() {
  require(LifecycleState::inactive, "activate");
  try {
    component_->on_activate();
  } catch (const std::exception& error) {
    fail("activate", error);
  }
  {
    std::lock_guard lock(mutex_);
    stats_ = LoopStats{};
    cycle_times_.clear();
  }
  state_ = LifecycleState::active;
  if (options_.rate_hz > 0.0) {
    loop_stop_ = false;
    period_ns_ = static_cast<std::int64_t>(std::llround(1e9 / options_.rate_hz));
    last_start_ns_ = -1;
    next_ns_ = context_.clock->now_ns();
    period_mean_s_ = period_m2_ = 0.0;
    periods_ = 0;
    on_event_thread_ = component_->event_driven() && component_->cycles_on_event_thread();
    if (on_event_thread_) {
      {
        std::lock_guard lock(cycle_mutex_);
        cycling_ = true;
      }
      component_->set_event_cycle(this);
    }
    loop_ = std::thread([this, watch = on_event_thread_] {
      if (watch) {
        run_watchdog();
      } else {
        run_loop();
      }
    });
  }
  lifecycle_event(EventSeverity::info, "INACTIVE -> ACTIVE");
  publish_status();
}

void ComponentRunner::stop_loop() {
  if (on_event_thread_) {
    {
      std::lock_guard lock(cycle_mutex_);  // after a cycle in progress
      cycling_ = false;
    }
    component_->set_event_cycle(nullptr);
    on_event_thread_ = false;
  }
  if (loop_.joinable()) {
    {
      std::lock_guard lock(cycle_mutex_);
      loop_stop_ = true;
    }
    watchdog_wake_.notify_all();
    context_.clock->wake();
    loop_.join();
  }
}

void ComponentRunner::deactivate() {
  require(LifecycleState::active, "deactivate");
  stop_loop();  // the cycle never overlaps a transition hook
  print_cycle_times();
  try {
    component_->on_deactivate();
  } catch (const std::exception& error) {
    fail("deactivate", error);
  }
  set_state(LifecycleState::inactive);
}

void ComponentRunner::cleanup() {
  require(LifecycleState::inactive, "cleanup");
  try {
    component_->on_cleanup();
  } catch (const std::exception& error) {
    fail("cleanup", error);
  }
  set_state(LifecycleState::unconfigured);
}

void ComponentRunner::shutdown() {
  if (state() == LifecycleState::finalized) {
    throw TransitionError("component '" + context_.instance + "': cannot shutdown from finalized");
  }
  stop_loop();
  std::string error;
  try {
    if (state() == LifecycleState::active) {
      component_->on_deactivate();
    }
    component_->on_shutdown();
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!error.empty()) {
    component_->report().set_error(error);
  }
  set_state(LifecycleState::finalized);
  if (!error.empty()) {
    throw TransitionError("component '" + context_.instance + "' (" + context_.type +
                          "): shutdown failed: " + error);
  }
}

LoopStats ComponentRunner::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::string ComponentRunner::last_error() const { return component_->report().last_error(); }

bool ComponentRunner::wait_for_event(std::int64_t period_ns) {
  try {
    return component_->wait_for_event(10 * period_ns);
  } catch (const std::exception& e) {
    component_->report().set_error(e.what());
    return false;
  }
}

// The periodic cycle. Ticks at start + k·period on the clock; a cycle that ends
// after its successor's tick is an overrun, and the missed ticks are skipped
// (never run back to back to catch up). An event-driven component's cycle
// starts at its event instead, and overruns when it takes longer than a period.
void ComponentRunner::run_loop() {
  Clock& clock = *context_.clock;
  const bool event_driven = component_->event_driven();
  while (!loop_stop_.load(std::memory_order_relaxed)) {
    if (event_driven ? !wait_for_event(period_ns_) : !clock.sleep_until(next_ns_)) {
      continue;  // no event yet, or woken early: stop requested, or spurious
    }
    run_cycle(event_driven);
  }
}

namespace {
// The runner whose cycle this thread is running, if any: in one process Fast
// DDS delivers in the writer's thread, so a cycle's own writes can bring an
// event back to this thread before the cycle ends.
thread_local const ComponentRunner* cycle_on_this_thread = nullptr;
}  // namespace

// The events' threads run the cycles; this thread runs one only when none ran
// for ten periods: at activation (an event that came before it, which no
// arrival will announce again) and when an event's inputs are late (the
// component's wait_for_event then waits for them, here, as the loop would).
void ComponentRunner::run_watchdog() {
  std::unique_lock lock(cycle_mutex_);
  std::uint64_t seen = cycles_run_;
  run_ready_cycles(false);
  while (!loop_stop_.load(std::memory_order_relaxed)) {
    watchdog_wake_.wait_for(lock, std::chrono::nanoseconds(10 * period_ns_),
                            [this] { return loop_stop_.load(std::memory_order_relaxed); });
    if (loop_stop_.load(std::memory_order_relaxed)) {
      break;
    }
    if (cycles_run_ == seen && wait_for_event(period_ns_)) {
      run_guarded_cycle(false);
      run_ready_cycles(false);
    }
    seen = cycles_run_;
  }
}

bool ComponentRunner::run() {
  if (cycle_on_this_thread == this) {
    return false;  // nested in our own cycle: answered when that cycle ends
  }
  std::lock_guard lock(cycle_mutex_);
  return cycling_ && run_ready_cycles(true);
}

// Caller holds cycle_mutex_. Runs a cycle while one is due: an event that
// arrived during a cycle (nested in it, or blocked on the lock) is answered
// at once, not ten periods later by the watchdog. A few at most: a component
// that stays ready after its cycle must not hold the thread.
bool ComponentRunner::run_ready_cycles(bool on_event_thread) {
  constexpr int kMostInARow = 4;
  for (int ran = 0; ran < kMostInARow; ++ran) {
    try {
      if (!component_->event_ready()) {
        return ran > 0;
      }
    } catch (const std::exception& e) {
      component_->report().set_error(e.what());
      return ran > 0;
    }
    run_guarded_cycle(on_event_thread);
  }
  return true;
}

void ComponentRunner::run_guarded_cycle(bool on_event_thread) {
  const ComponentRunner* outer = cycle_on_this_thread;
  cycle_on_this_thread = this;
  run_cycle(true, on_event_thread);
  cycle_on_this_thread = outer;
}

// Statistics use Welford's running mean/variance: no allocation, no lock held
// while the component runs.
void ComponentRunner::run_cycle(bool event_driven, bool on_event_thread) {
  const std::int64_t period_ns = period_ns_;
  Clock& clock = *context_.clock;
  const std::int64_t start_ns = clock.now_ns();
  const auto started = std::chrono::steady_clock::now();
  bool error = false;
  std::string what;
  try {
    component_->read(start_ns, period_ns);
    component_->update(start_ns, period_ns);
    component_->write(start_ns, period_ns);
  } catch (const std::exception& e) {
    error = true;
    what = e.what();  // allocation only on the error path
  }
  const std::int64_t end_ns = clock.now_ns();
  const auto took = std::chrono::steady_clock::now() - started;
  next_ns_ += period_ns;
  bool overrun = false;
  if (event_driven) {
    overrun = end_ns - start_ns > period_ns;
  } else if (end_ns > next_ns_) {
    overrun = true;
    next_ns_ += ((end_ns - next_ns_) / period_ns + 1) * period_ns;  // skip the missed ticks
  }
  if (error) {
    component_->report().set_error(what);
  }
  ++cycles_run_;
  std::lock_guard lock(mutex_);
  LoopStats& s = stats_;
  ++s.iterations;
  s.overruns += overrun ? 1 : 0;
  s.errors += error ? 1 : 0;
  s.on_event_thread += on_event_thread ? 1 : 0;
  const double cycle_s = 1e-9 * static_cast<double>(end_ns - start_ns);
  s.cycle_mean_s += (cycle_s - s.cycle_mean_s) / static_cast<double>(s.iterations);
  s.cycle_max_s = std::max(s.cycle_max_s, cycle_s);
  cycle_times_.add(took);
  if (last_start_ns_ >= 0) {
    const double period_s = 1e-9 * static_cast<double>(start_ns - last_start_ns_);
    ++periods_;
    const double delta = period_s - period_mean_s_;
    period_mean_s_ += delta / static_cast<double>(periods_);
    period_m2_ += delta * (period_s - period_mean_s_);
    s.period_mean_s = period_mean_s_;
    s.period_jitter_s =
        periods_ > 1 ? std::sqrt(period_m2_ / static_cast<double>(periods_ - 1)) : 0.0;
    s.period_max_s = std::max(s.period_max_s, period_s);
  }
  last_start_ns_ = start_ns;
}

// One line at the end of a periodic component's run, e.g. "balance: 21003
// cycles, read + update + write mean 0.071 ms (p99 0.09 ms); 21002 on their
// event's thread": with the robot's lockstep line, where a tick went.
void ComponentRunner::print_cycle_times() {
  std::string line;
  {
    std::lock_guard lock(mutex_);
    if (cycle_times_.count() == 0) {
      return;
    }
    line = context_.instance + ": " + std::to_string(cycle_times_.count()) +
           " cycles, read + update + write " + cycle_times_.mean_and_p99();
    if (component_->event_driven() && component_->cycles_on_event_thread()) {
      line += "; " + std::to_string(stats_.on_event_thread) + " on their event's thread";
    }
  }
  print_line(stdout, line);
}

void ComponentRunner::publish_status() {
  {
    std::lock_guard lock(status_->mutex);
    ++status_->kicks;
  }
  status_->kicked.notify_all();
}

void ComponentRunner::run_heartbeat() {
  Status& status = *status_;
  std::unique_lock lock(status.mutex);
  std::uint64_t seen = status.kicks;
  bool first = true;
  while (!status.stop) {
    if (!first) {
      const auto woken = [&] { return status.stop || status.kicks != seen; };
      if (options_.status_period_s > 0.0) {
        status.kicked.wait_for(lock, std::chrono::duration<double>(options_.status_period_s),
                               woken);
      } else {
        status.kicked.wait(lock, woken);
      }
    }
    first = false;
    seen = status.kicks;
    const LoopStats s = stats();
    msg::ComponentStatus& sample = status.sample;
    sample.header().stamp_ns(context_.clock->now_ns());
    sample.state(msg::to_wire(state()));
    sample.period_mean_s(s.period_mean_s);
    sample.period_jitter_s(s.period_jitter_s);
    sample.overruns(s.overruns);
    sample.iterations(s.iterations);
    copy_report(component_->report(), sample);
    status.publisher.publish(sample);
    sample.header().seq(sample.header().seq() + 1);
  }
}

}  // namespace wbi::runtime
