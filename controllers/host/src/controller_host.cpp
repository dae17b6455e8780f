#include "wbi/controllers/controller_host.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wbi::controllers {

struct ControllerHost::Hosted {
  std::string name, type;
  std::unique_ptr<Controller> controller;
  std::unique_ptr<ParameterTable> parameters;
  std::vector<std::unique_ptr<ReferenceInput>> inputs;  // one per declared reference
  std::vector<std::uint64_t> stale_said;                // per input: episodes printed
  bool configured = false;
  bool ran = false;  // was active at least once: its summary is printed
  std::string configure_error = "not configured";
};

namespace {
std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", t);
  return text;
}
}  // namespace

ControllerHost::ControllerHost(WholeBodyInterface& robot, runtime::StatusReport& report,
                               runtime::EventLog& events, Options options)
    : robot_(robot),
      report_(report),
      events_(events),
      options_(options),
      measured_(robot.dofs()),
      last_command_(Eigen::VectorXd::Zero(robot.dofs())),
      before_switch_(Eigen::VectorXd::Zero(robot.dofs())),
      blend_(Eigen::VectorXd::Zero(robot.dofs())),
      switches_(&report.counter("switches")),
      refused_(&report.counter("refused_switches")),
      fallbacks_(&report.counter("fallbacks")),
      stale_(&report.counter("stale_cycles")),
      late_(&report.counter("late_services")),
      overruns_(&report.counter("overruns")),
      changes_(&report.counter("parameter_changes")),
      late_references_(&report.counter("late_references")),
      stale_references_(&report.counter("stale_reference_ticks")) {}

ControllerHost::~ControllerHost() = default;

ControllerHost::Hosted& ControllerHost::find(const std::string& name) const {
  for (const auto& hosted : hosted_) {
    if (hosted->name == name) {
      return *hosted;
    }
  }
  std::string known;
  for (const auto& hosted : hosted_) {
    known += (known.empty() ? "" : ", ") + hosted->name;
  }
  throw Error("unknown controller '" + name + "' (hosted: " + (known.empty() ? "none" : known) +
              ")");
}

ParameterTable& ControllerHost::add(const std::string& name, const std::string& type,
                                    std::unique_ptr<Controller> controller) {
  for (const auto& hosted : hosted_) {
    if (hosted->name == name) {
      throw Error("controller '" + name + "' is hosted twice");
    }
  }
  auto hosted = std::make_unique<Hosted>();
  hosted->name = name;
  hosted->type = type;
  hosted->parameters = std::make_unique<ParameterTable>(name, controller->parameters());
  hosted->parameters->size_for(robot_.dofs());
  std::vector<ReferenceInput*> inputs;
  for (auto& spec : controller->references()) {
    const std::string owner = name + "/" + spec.name;
    hosted->inputs.push_back(std::make_unique<ReferenceInput>(owner, std::move(spec)));
    inputs.push_back(hosted->inputs.back().get());
  }
  hosted->stale_said.assign(inputs.size(), 0);
  controller->bind_references(inputs);
  hosted->controller = std::move(controller);
  hosted_.push_back(std::move(hosted));
  return *hosted_.back()->parameters;
}

void ControllerHost::configure(const std::string& name) {
  Hosted& hosted = find(name);
  try {
    hosted.controller->configure(robot_, *hosted.parameters);
    hosted.configured = true;
    hosted.configure_error.clear();
  } catch (const std::exception& e) {
    hosted.configured = false;
    hosted.configure_error = e.what();
    throw Error(std::string("controller '") + name + "' did not configure: " + e.what());
  }
}

void ControllerHost::set_initial(const std::string& name) {
  Hosted& hosted = find(name);
  if (!hosted.configured) {
    throw Error("controller '" + name + "' cannot start: " + hosted.configure_error);
  }
  initial_ = &hosted;
}

const std::string& ControllerHost::active() const {
  static const std::string none;
  std::lock_guard lock(switch_mutex_);
  return active_ ? active_->name : none;
}

Controller* ControllerHost::active_controller() {
  return active_ ? active_->controller.get() : nullptr;
}

bool ControllerHost::activate(Hosted& hosted, bool first_start) {
  try {
    robot_.state().read_robot_state(measured_, ReadMode::latest);
  } catch (const StaleDataError&) {
    stale_->add();
    return false;  // no state to continue from: tried again at the next tick
  }
  for (auto& input : hosted.inputs) {
    input->reset_episode();
  }
  hosted.controller->activate(measured_);
  // At a switch, the new controller's commands start from the last one sent.
  blend_pending_ = !first_start && options_.blend_s > 0.0;
  blending_ = false;
  std::lock_guard lock(switch_mutex_);
  active_ = &hosted;
  hosted.ran = true;
  overruns_in_a_row_ = 0;
  return true;
}

void ControllerHost::deactivate(Hosted& hosted) {
  try {
    hosted.controller->deactivate();
  } catch (const std::exception& e) {
    report_.set_error("controller '" + hosted.name + "' threw in deactivate: " + e.what());
  }
  std::lock_guard lock(switch_mutex_);
  if (active_ == &hosted) {
    active_ = nullptr;
  }
}

void ControllerHost::fall_back(const std::string& reason, double time_s) {
  const std::string from = active_ ? active_->name : std::string("none");
  if (active_) {
    deactivate(*active_);
  }
  fallbacks_->add();
  std::string line = "controller '" + from + "' " + reason + ": fell back to '" + kHoldController +
                     "' at t = " + seconds(time_s);
  Hosted* hold = nullptr;
  try {
    hold = &find(kHoldController);
  } catch (const Error&) {
  }
  if (from == kHoldController || !hold || !hold->configured) {
    line = "controller '" + from + "' " + reason + ": no controller active (" +
           (from == kHoldController ? "hold itself failed" : "no hold configured") +
           "); the robot's watchdog takes over";
  } else {
    try {
      if (!activate(*hold, false)) {
        initial_ = hold;  // activated at the first tick with a fresh state
      }
    } catch (const TimeoutError& e) {
      line += std::string("; hold did not activate yet (tried again each tick): ") + e.what();
      initial_ = hold;
    } catch (const std::exception& e) {
      line += std::string("; hold did not activate: ") + e.what();
    }
  }
  report_.set_error(line);
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
  events_.emit(EventSeverity::warning, EventKind::controller_fallback, line);
}

bool ControllerHost::apply_switch(double time_s) {
  std::unique_lock lock(switch_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !switch_.pending) {
    return false;  // the requester holds the lock for a moment: at the next tick
  }
  Hosted* from = switch_.deactivate;
  Hosted* to = switch_.activate;
  lock.unlock();
  if (from) {
    deactivate(*from);
  }
  bool activated = true;
  std::string failure;
  if (to) {
    try {
      activated = activate(*to, false);
      if (!activated) {
        failure = "no fresh state to activate it from";
      }
    } catch (const std::exception& e) {
      activated = false;
      failure = e.what();
    }
  }
  lock.lock();
  switch_.result.time_s = time_s;
  switch_.result.from = from ? from->name : std::string("none");
  switch_.result.to = to ? to->name : std::string("none");
  if (activated) {
    switch_.result.done = true;
    switch_.result.text = (from ? from->name : std::string("none")) + " → " +
                          (to ? to->name : std::string("none")) + " at t = " + seconds(time_s);
  } else {
    switch_.result.text = "'" + to->name + "' did not activate: " + failure;
  }
  lock.unlock();
  if (!activated && from) {
    fall_back("was switched out but '" + to->name + "' did not activate (" + failure + ")", time_s);
  }
  return true;
}

void ControllerHost::run_active(double time_s, double period_s) {
  Hosted& hosted_active = *active_;  // a fallback in update() changes active_
  Controller& controller = *active_->controller;
  ParameterTable& parameters = *active_->parameters;
  if (state_source_changed_.exchange(false)) {
    controller.state_source_changed();
  }
  if (parameters.apply_staged()) {
    controller.parameters_changed(parameters);
    changes_->add();
    parameters_applied_ = true;
  }
  const auto start = std::chrono::steady_clock::now();
  bool fresh = false;
  try {
    fresh = controller.update(time_s, period_s);
  } catch (const StaleDataError&) {
    stale_->add();  // no fresh state this tick: no command; the robot's watchdog guards
    return;
  } catch (const TimeoutError&) {
    // A service it needs is late (a remote model restarting): the controller
    // is not at fault, and hold would need the same service. Tried again next tick.
    late_->add();
    return;
  } catch (const std::exception& e) {
    fall_back(std::string("threw in update (") + e.what() + ")", time_s);
    if (active_ && active_ != &hosted_active) {
      run_active(time_s, period_s);  // hold commands this tick already: no tick goes unanswered
    }
    return;
  }
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_references(hosted_active, time_s);
  if (took_s > period_s) {
    overruns_->add();
    if (++overruns_in_a_row_ >= options_.overrun_limit && options_.overrun_limit > 0) {
      char reason[128];
      std::snprintf(reason, sizeof reason,
                    "overran its %.3f ms period %d ticks in a row (last %.3f ms)", 1e3 * period_s,
                    overruns_in_a_row_, 1e3 * took_s);
      fall_back(reason, time_s);
    }
  } else {
    overruns_in_a_row_ = 0;
  }
  if (fresh && active_ == &hosted_active) {
    send(time_s);
  }
}

void ControllerHost::send(double time_s) {
  const Eigen::VectorXd& command = active_->controller->command();
  if (blend_pending_) {  // the first command after a switch: keep the difference to the last
    blend_ = last_command_ - command;
    blend_pending_ = false;
    blending_ = true;
    blend_start_s_ = time_s;
  }
  double weight = 0.0;
  if (blending_) {
    weight = std::exp(-(time_s - blend_start_s_) / options_.blend_s);
    blending_ = weight > 1e-9;
  }
  // How smooth the commands are: the change since the last tick.
  const double change = (command + weight * blend_ - last_command_).norm();
  if (settle_until_s_ >= 0.0) {
    settling_.largest_change = std::max(settling_.largest_change, change);
  } else {
    largest_change_ = std::max(largest_change_, change);
  }
  if (weight > 0.0) {
    last_command_ = command + weight * blend_;
  } else {
    last_command_ = command;
  }
  robot_.actuators().set_control_reference(last_command_);
}

void ControllerHost::tick(double time_s, double period_s) {
  if (initial_ && !active_) {
    try {
      if (activate(*initial_, true)) {
        initial_ = nullptr;
      }
    } catch (const TimeoutError&) {
      late_->add();  // a service it needs is late: tried again at the next tick
    } catch (const std::exception& e) {
      initial_ = nullptr;
      fall_back(std::string("threw in activate (") + e.what() + ")", time_s);
    }
  }
  const bool switching = switch_requested_.load(std::memory_order_acquire) && apply_switch(time_s);
  // Inactive controllers take their staged values too (they use them when activated).
  for (auto& hosted : hosted_) {
    if (hosted.get() != active_ && hosted->configured && hosted->parameters->apply_staged()) {
      hosted->controller->parameters_changed(*hosted->parameters);
      changes_->add();
      parameters_applied_ = true;
    }
  }
  if (switching) {
    before_switch_ = last_command_;
  }
  if (active_) {
    run_active(time_s, period_s);
  }
  if (switching) {
    finish_switch();
  }
  if (parameters_applied_) {
    wake_parameter_waiters();
  }
  if (settle_until_s_ >= 0.0 && time_s >= settle_until_s_) {
    settle_until_s_ = -1.0;
    if (settling_.torque_before > 0.0) {
      settling_.largest_change /= settling_.torque_before;
    }
    settling_.settled_after_s = time_s - settling_.time_s;
    ++switches_settled_;
  }
}

// Loop thread: wakes wait_for_parameters(), never blocking. The generation
// changed before this, so a waiter that checks it after we took the lock sees
// the change, and one that checked it before is asleep by then (it held the
// lock from its check to its wait). Lock taken by a waiter right now: tried
// again at the next tick.
void ControllerHost::wake_parameter_waiters() {
  std::unique_lock lock(applied_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) {
    return;
  }
  lock.unlock();
  applied_.notify_all();  // no allocation; a futex wake only when someone waits
  parameters_applied_ = false;
}

// After the switch tick's command: its step, then the requester is answered.
void ControllerHost::finish_switch() {
  std::unique_lock lock(switch_mutex_);
  if (!switch_.pending) {
    return;
  }
  if (switch_.result.done && active_) {
    // The first command sent after the switch against the last one before it.
    const double before = before_switch_.norm();
    switch_.result.torque_step =
        before > 0.0 ? (last_command_ - before_switch_).norm() / before : 0.0;
    char step[96];
    std::snprintf(step, sizeof step, "; torque step %.2f %% of the %.3g N m applied",
                  100.0 * switch_.result.torque_step, before);
    switch_.result.text += step;
    switch_.result.torque_before = before;
    switch_.result.largest_change_before = before > 0.0 ? largest_change_ / before : 0.0;
    largest_change_ = 0.0;
    settling_ = switch_.result;
    settling_.largest_change = 0.0;
    settle_until_s_ = switch_.result.time_s + std::max(5.0 * options_.blend_s, 0.05);
  }
  switch_.pending = false;
  switch_requested_.store(false, std::memory_order_release);
  last_switch_ = switch_.result;
  ++switches_done_;
  lock.unlock();
  switch_done_.notify_all();
  if (last_switch_.done) {  // one that did not activate fell back: that is its event
    events_.emit(EventSeverity::info, EventKind::controller_switched, last_switch_.text);
  }
}

SwitchResult ControllerHost::check_switch(Hosted* to, Hosted* from) const {
  SwitchResult refused;
  if (switch_.pending) {
    refused.text = "another switch is pending";
  } else if (to && !to->configured) {
    refused.text = "'" + to->name + "' cannot be activated: " + to->configure_error;
  } else if (from && from != active_) {
    refused.text = "'" + from->name +
                   "' is not active (active: " + (active_ ? active_->name : std::string("none")) +
                   ")";
  } else if (to && to == active_ && from != to) {
    refused.text = "'" + to->name + "' is already active";
  } else if (to && active_ && !from) {
    refused.text = "'" + active_->name + "' is active on the same joints: deactivate it in the " +
                   "same switch (--deactivate " + active_->name + ")";
  } else if (!to) {
    refused.text = std::string("nothing would command the joints: activate '") + kHoldController +
                   "' to hold the posture";
  }
  return refused;
}

SwitchResult ControllerHost::request_switch(const std::vector<std::string>& activate,
                                            const std::vector<std::string>& deactivate) {
  SwitchResult refused;
  const auto refuse = [&](std::string text) {
    refused_->add();
    refused.text = std::move(text);
    return refused;
  };
  if (activate.size() > 1 || deactivate.size() > 1) {
    return refuse(
        "the host runs one controller at a time on its joints: name at most one to "
        "activate and one to deactivate");
  }
  Hosted* to = nullptr;
  Hosted* from = nullptr;
  try {
    to = activate.empty() ? nullptr : &find(activate[0]);
    from = deactivate.empty() ? nullptr : &find(deactivate[0]);
  } catch (const Error& e) {
    return refuse(e.what());
  }
  std::unique_lock lock(switch_mutex_);
  if (const SwitchResult problem = check_switch(to, from); !problem.text.empty()) {
    return refuse(problem.text);
  }
  switch_ = PendingSwitch{.pending = true, .activate = to, .deactivate = from, .result = {}};
  switch_requested_.store(true, std::memory_order_release);
  const std::uint64_t id = switches_done_;
  const bool applied =
      switch_done_.wait_for(lock, options_.switch_timeout, [&] { return switches_done_ > id; });
  if (!applied) {
    switch_.pending = false;
    switch_requested_.store(false, std::memory_order_release);
    return refuse("the switch did not take effect within " +
                  std::to_string(options_.switch_timeout.count()) +
                  " ms: is the host's loop running?");
  }
  if (switch_.result.done) {
    switches_->add();
  } else {
    refused_->add();
  }
  return switch_.result;
}

std::string ControllerHost::schedule_switch(const std::string& activate) {
  Hosted* to = nullptr;
  try {
    to = &find(activate);
  } catch (const Error& e) {
    refused_->add();
    return e.what();
  }
  std::lock_guard lock(switch_mutex_);
  if (const SwitchResult problem = check_switch(to, active_); !problem.text.empty()) {
    refused_->add();
    return problem.text;
  }
  switch_ = PendingSwitch{.pending = true, .activate = to, .deactivate = active_, .result = {}};
  switch_requested_.store(true, std::memory_order_release);
  switches_->add();  // applied by the next tick
  return "";
}

void ControllerHost::set_parameter(const std::string& controller, const std::string& parameter,
                                   const std::vector<double>& values) {
  Hosted& hosted = find(controller);
  const std::size_t index = hosted.parameters->index(parameter);
  bool active = false;
  {
    std::lock_guard lock(switch_mutex_);
    active = active_ == &hosted;
  }
  hosted.parameters->stage(index, values, active);
  const std::string& unit = hosted.parameters->spec(index).unit;
  events_.emit(EventSeverity::info, EventKind::parameter_changed,
               controller + "." + parameter + " = " + format_values(values) +
                   (unit.empty() ? "" : " " + unit) + " (from the next tick)");
}

bool ControllerHost::wait_for_parameters(const std::string& controller, std::uint64_t generation,
                                         std::chrono::nanoseconds timeout) const {
  const ParameterTable& table = *find(controller).parameters;
  std::unique_lock lock(applied_mutex_);
  return applied_.wait_for(lock, timeout, [&] { return table.generation() != generation; });
}

const ParameterTable& ControllerHost::parameters(const std::string& controller) const {
  return *find(controller).parameters;
}

std::vector<ControllerInfo> ControllerHost::list() const {
  std::lock_guard lock(switch_mutex_);
  std::vector<ControllerInfo> out;
  for (const auto& hosted : hosted_) {
    out.push_back({hosted->name, hosted->type, hosted.get() == active_, hosted->configure_error});
  }
  return out;
}

// A stale reference is the controller's to handle (its declared rule); the
// host keeps the status counters at the inputs' totals and says once per
// episode that the rule applies.
void ControllerHost::report_references(Hosted& active, double time_s) {
  std::uint64_t stale = 0, late = 0;
  for (const auto& hosted : hosted_) {
    for (const auto& input : hosted->inputs) {
      stale += input->stale_ticks();
      late += input->late();
    }
  }
  stale_references_->set(stale);
  late_references_->set(late);
  for (std::size_t i = 0; i < active.inputs.size(); ++i) {
    const ReferenceInput& input = *active.inputs[i];
    if (input.stale_episodes() != active.stale_said[i]) {
      active.stale_said[i] = input.stale_episodes();
      char line[256];
      std::snprintf(line, sizeof line,
                    "t = %.3f s: reference %s stale (older than %.3f s): rule %s", time_s,
                    input.owner().c_str(), input.spec().max_age_s, to_string(input.spec().rule));
      std::fprintf(stderr, "%s\n", line);
      events_.emit(EventSeverity::warning, EventKind::reference_stale, line, input.owner());
    }
  }
}

std::vector<ReferenceInput*> ControllerHost::references(const std::string& controller) const {
  std::vector<ReferenceInput*> inputs;
  for (const auto& input : find(controller).inputs) {
    inputs.push_back(input.get());
  }
  return inputs;
}

void ControllerHost::set_reference_wait(std::int64_t wait_ns) {
  reference_wait_ns_ = wait_ns;
  for (auto& hosted : hosted_) {
    for (auto& input : hosted->inputs) {
      input->set_wait(wait_ns);
    }
  }
}

bool ControllerHost::wait_for_first_references(std::int64_t time_ns) {
  bool all = true;
  for (auto& hosted : hosted_) {
    for (auto& input : hosted->inputs) {
      all = input->wait_for(time_ns, reference_wait_ns_) && all;
    }
  }
  return all;
}

std::string ControllerHost::summary() const {
  std::lock_guard lock(switch_mutex_);
  std::string text;
  const auto line = [&](const std::string& own) {
    text += text.empty() ? "" : "\n";
    text += own;
  };
  for (const auto& hosted : hosted_) {
    if (const std::string own = hosted->ran ? hosted->controller->summary() : ""; !own.empty()) {
      line(own);
    }
    for (const auto& input : hosted->inputs) {
      line(input->summary());
    }
  }
  return text;
}

}  // namespace wbi::controllers
