// The controller host's setup and its tick: run the active controllers (each
// on its joints, hold on the free ones), compose one command, blend the joints
// that changed hands, send. Switches and fallbacks: controller_host_switch.cpp.
#include "wbi/controllers/controller_host.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "controller_host_hosted.hpp"

namespace wbi::controllers {

ControllerHost::ControllerHost(WholeBodyInterface& robot, runtime::StatusReport& report,
                               runtime::EventLog& events, Options options)
    : robot_(robot),
      report_(report),
      events_(events),
      options_(options),
      owner_(static_cast<std::size_t>(robot.dofs()), nullptr),
      measured_(robot.dofs()),
      pinned_(std::make_unique<PinnedState>(PinnedState{RobotState(robot.dofs()), false})),
      command_(Eigen::VectorXd::Zero(robot.dofs())),
      last_command_(Eigen::VectorXd::Zero(robot.dofs())),
      before_switch_(Eigen::VectorXd::Zero(robot.dofs())),
      blend_(Eigen::VectorXd::Zero(robot.dofs())),
      blend_start_s_(Eigen::VectorXd::Zero(robot.dofs())),
      blend_pending_(static_cast<std::size_t>(robot.dofs()), 0),
      blending_(static_cast<std::size_t>(robot.dofs()), 0),
      switched_(static_cast<std::size_t>(robot.dofs()), 0),
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
  hosted->chained.assign(inputs.size(), 0);
  controller->bind_references(inputs);
  std::vector<ReferenceOutput*> outputs;
  for (auto& spec : controller->outputs()) {
    const std::string owner = name + "/" + spec.name;
    hosted->outputs.push_back(std::make_unique<ReferenceOutput>(owner, std::move(spec)));
    outputs.push_back(hosted->outputs.back().get());
  }
  controller->bind_outputs(outputs);
  if (controller->commands_joints()) {
    for (int j = 0; j < robot_.dofs(); ++j) {
      hosted->joints.push_back(j);
    }
  }
  hosted->controller = std::move(controller);
  if (name == kHoldController) {
    hold_ = hosted.get();
  }
  hosted_.push_back(std::move(hosted));
  active_.reserve(hosted_.size());
  running_.reserve(hosted_.size());
  tick_order_.reserve(hosted_.size());
  running_controllers_.reserve(hosted_.size());
  return *hosted_.back()->parameters;
}

void ControllerHost::set_joints(const std::string& name, const std::vector<std::string>& joints) {
  Hosted& hosted = find(name);
  if (&hosted == hold_) {
    throw Error("controller 'hold' takes whatever joints no other controller commands");
  }
  const IdList& all = robot_.joint_list();
  std::vector<int> indices;
  for (const auto& joint : joints) {
    const auto it = std::find(all.begin(), all.end(), joint);
    if (it == all.end()) {
      std::string known;
      for (const auto& own : all) {
        known += (known.empty() ? "" : ", ") + own;
      }
      throw Error("controller '" + name + "': joint '" + joint + "' is not the host's (" + known +
                  ")");
    }
    const int index = static_cast<int>(it - all.begin());
    if (std::find(indices.begin(), indices.end(), index) != indices.end()) {
      throw Error("controller '" + name + "': joint '" + joint + "' is named twice");
    }
    indices.push_back(index);
  }
  std::sort(indices.begin(), indices.end());
  hosted.joints = std::move(indices);
}

void ControllerHost::chain(const std::string& downstream, const std::string& input,
                           const std::string& upstream, const std::string& output) {
  Hosted& to = find(downstream);
  Hosted& from = find(upstream);
  const auto named = [](const auto& list, const std::string& wanted, const std::string& owner,
                        const char* what) -> std::size_t {
    std::string known;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (list[i]->spec().name == wanted) {
        return i;
      }
      known += (known.empty() ? "" : ", ") + list[i]->spec().name;
    }
    throw Error("controller '" + owner + "' has no reference " + what + " '" + wanted + "' (" +
                (known.empty() ? std::string("none") : known) + ")");
  };
  const std::size_t in = named(to.inputs, input, downstream, "input");
  const std::size_t out = named(from.outputs, output, upstream, "output");
  if (&to == &from || to.feeds(from)) {
    throw Error("chaining " + upstream + " into " + downstream + " makes a cycle");
  }
  if (to.chained[in]) {
    throw Error("the reference input " + downstream + "/" + input + " is chained already");
  }
  from.outputs[out]->connect(*to.inputs[in]);
  to.chained[in] = 1;
  pin_state_ = true;  // a planner and what it feeds answer the same state
  if (std::find(to.upstream.begin(), to.upstream.end(), &from) == to.upstream.end()) {
    to.upstream.push_back(&from);
  }
  if (std::find(from.downstream.begin(), from.downstream.end(), &to) == from.downstream.end()) {
    from.downstream.push_back(&to);
  }
}

void ControllerHost::configure(const std::string& name) {
  Hosted& hosted = find(name);
  hosted.view = std::make_unique<JointSetInterface>(robot_, name, hosted.joints, *pinned_);
  hosted.controller->bind_joints(hosted.joints);
  try {
    hosted.controller->configure(*hosted.view, *hosted.parameters);
    hosted.configured = true;
    hosted.configure_error.clear();
  } catch (const std::exception& e) {
    hosted.configured = false;
    hosted.configure_error = e.what();
    throw Error(std::string("controller '") + name + "' did not configure: " + e.what());
  }
}

std::string ControllerHost::active() const {
  std::lock_guard lock(switch_mutex_);
  std::string names;
  for (const Hosted* hosted : active_) {
    names += (names.empty() ? "" : ", ") + hosted->name;
  }
  if (hold_active_) {
    names += (names.empty() ? "" : ", ") + std::string(kHoldController);
  }
  return names;
}

Controller* ControllerHost::active_controller() {
  for (std::size_t i = 0; i < running_.size(); ++i) {
    if (!running_[i]->joints.empty()) {
      return running_controllers_[i];  // a planner's progress and signals are not the host's
    }
  }
  return running_controllers_.empty() ? nullptr : running_controllers_.front();
}

void ControllerHost::rebuild_running() {
  // As activated, each planner placed just before the first controller it feeds.
  std::vector<Hosted*> ordered;
  ordered.reserve(active_.size());
  const std::function<void(Hosted*)> place = [&](Hosted* hosted) {
    if (std::find(ordered.begin(), ordered.end(), hosted) != ordered.end()) {
      return;
    }
    for (Hosted* up : hosted->upstream) {
      if (up->active) {
        place(up);  // chain() refuses cycles
      }
    }
    ordered.push_back(hosted);
  };
  for (Hosted* hosted : active_) {
    place(hosted);
  }
  std::lock_guard lock(switch_mutex_);
  active_ = std::move(ordered);
  running_ = active_;
  if (hold_active_) {
    running_.push_back(hold_);
  }
  running_controllers_.clear();
  for (Hosted* hosted : running_) {
    running_controllers_.push_back(hosted->controller.get());
  }
}

int ControllerHost::run(Hosted& hosted, double time_s, double period_s, bool source_changed) {
  Controller& controller = *hosted.controller;
  if (source_changed) {
    controller.state_source_changed();
  }
  if (hosted.parameters->apply_staged()) {
    controller.parameters_changed(*hosted.parameters);
    changes_->add();
    parameters_applied_ = true;
  }
  const auto start = std::chrono::steady_clock::now();
  bool fresh = false;
  try {
    fresh = controller.update(time_s, period_s);
  } catch (const StaleDataError&) {
    stale_->add();  // no fresh state this tick: no command; the robot's watchdog guards
    return 0;
  } catch (const TimeoutError&) {
    // A service it needs is late (a remote model restarting): the controller
    // is not at fault, and hold would need the same service. Tried again next tick.
    late_->add();
    return 0;
  } catch (const std::exception& e) {
    fall_back(hosted, std::string("threw in update (") + e.what() + ")", time_s);
    return -1;
  }
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_references(hosted, time_s);
  if (took_s > period_s) {
    overruns_->add();
    if (++hosted.overruns_in_a_row >= options_.overrun_limit && options_.overrun_limit > 0) {
      char reason[128];
      std::snprintf(reason, sizeof reason,
                    "overran its %.3f ms period %d ticks in a row (last %.3f ms)", 1e3 * period_s,
                    hosted.overruns_in_a_row, 1e3 * took_s);
      fall_back(hosted, reason, time_s);
      return -1;
    }
  } else {
    hosted.overruns_in_a_row = 0;
  }
  if (!fresh) {
    return 0;
  }
  if (hosted.joints.empty()) {
    return 1;  // a planner: its outputs are written
  }
  const Eigen::VectorXd& command = controller.command();
  if (command.size() != robot_.dofs()) {
    char reason[128];
    std::snprintf(reason, sizeof reason, "gave a command of %d values for the host's %d joints",
                  static_cast<int>(command.size()), robot_.dofs());
    fall_back(hosted, reason, time_s);
    return -1;
  }
  for (const int j : hosted.joints) {
    if (owner_[static_cast<std::size_t>(j)] == &hosted ||
        (&hosted == hold_ && owner_[static_cast<std::size_t>(j)] == nullptr)) {
      command_[j] = command[j];
    }
  }
  return 1;
}

void ControllerHost::send(double time_s) {
  for (int j = 0; j < command_.size(); ++j) {
    const auto k = static_cast<std::size_t>(j);
    if (blend_pending_[k]) {  // its first command after a switch: keep the difference to the last
      blend_pending_[k] = 0;
      blend_[j] = last_command_[j] - command_[j];
      blend_start_s_[j] = time_s;
      blending_joints_ += blending_[k] ? 0 : 1;
      blending_[k] = 1;
    }
  }
  // The new command: the controllers' plus what remains of each joint's blend.
  double change_squared = 0.0;
  for (int j = 0; j < command_.size(); ++j) {
    const auto k = static_cast<std::size_t>(j);
    double out = command_[j];
    if (blending_[k]) {
      const double weight = std::exp(-(time_s - blend_start_s_[j]) / options_.blend_s);
      if (!(weight > 1e-9)) {
        blending_[k] = 0;
        --blending_joints_;
      }
      if (weight > 0.0) {
        out = command_[j] + weight * blend_[j];
      }
    }
    change_squared += (out - last_command_[j]) * (out - last_command_[j]);
    last_command_[j] = out;
  }
  // How smooth the commands are: the change since the last tick.
  const double change = std::sqrt(change_squared);
  if (settle_until_s_ >= 0.0) {
    settling_.largest_change = std::max(settling_.largest_change, change);
  } else {
    largest_change_ = std::max(largest_change_, change);
  }
  robot_.actuators().set_control_reference(last_command_);
}

void ControllerHost::tick(double time_s, double period_s) {
  if (!started_) {
    started_ = start(time_s);
  } else if (hold_pending_) {
    take_free_joints_to_hold();
  }
  const bool switching = switch_requested_.load(std::memory_order_acquire) && apply_switch(time_s);
  // Inactive controllers take their staged values too (they use them when activated).
  for (auto& hosted : hosted_) {
    if (!is_running(*hosted) && hosted->configured && hosted->parameters->apply_staged()) {
      hosted->controller->parameters_changed(*hosted->parameters);
      changes_->add();
      parameters_applied_ = true;
    }
  }
  if (switching) {
    before_switch_ = last_command_;
  }
  const bool source_changed = state_source_changed_.exchange(false);
  if (pin_state_) {  // one state for the whole tick (joint_set_interface.hpp)
    try {
      robot_.state().read_robot_state(pinned_->state, ReadMode::latest);
      pinned_->valid = true;
    } catch (const StaleDataError&) {
      pinned_->valid = false;  // each controller meets it in its own read
    }
  }
  // One command when every controller on joints had something new (each
  // answers the same state); a planner's outputs do not count. A fallback
  // changes running_: this tick runs the controllers that were running and
  // still are, then hold when it took joints meanwhile.
  bool any = false, all = true, hold_ran = false;
  const auto run_one = [&](Hosted& hosted) {
    const int ran = run(hosted, time_s, period_s, source_changed);
    if (ran >= 0 && !hosted.joints.empty()) {
      any = any || ran > 0;
      all = all && ran > 0;
    }
  };
  tick_order_.assign(running_.begin(), running_.end());  // capacity reserved: no allocation
  for (Hosted* hosted : tick_order_) {
    if (is_running(*hosted)) {
      hold_ran = hold_ran || hosted == hold_;
      run_one(*hosted);
    }
  }
  if (hold_active_ && !hold_ran) {
    run_one(*hold_);
  }
  pinned_->valid = false;
  count_references();
  if (any && all) {
    send(time_s);
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

void ControllerHost::set_parameter(const std::string& controller, const std::string& parameter,
                                   const std::vector<double>& values) {
  Hosted& hosted = find(controller);
  const std::size_t index = hosted.parameters->index(parameter);
  bool active = false;
  {
    std::lock_guard lock(switch_mutex_);
    active = is_running(hosted);
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
    out.push_back({hosted->name, hosted->type, is_running(*hosted), hosted->configure_error});
  }
  return out;
}

// The status counters at the inputs' totals, once per tick.
void ControllerHost::count_references() {
  std::uint64_t stale = 0, late = 0;
  for (const auto& hosted : hosted_) {
    for (const auto& input : hosted->inputs) {
      stale += input->stale_ticks();
      late += input->late();
    }
  }
  stale_references_->set(stale);
  late_references_->set(late);
}

// A stale reference is the controller's to handle (its declared rule); the
// host says once per episode that the rule applies.
void ControllerHost::report_references(Hosted& active, double time_s) {
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
  const Hosted& hosted = find(controller);
  std::vector<ReferenceInput*> inputs;
  for (std::size_t i = 0; i < hosted.inputs.size(); ++i) {
    if (!hosted.chained[i]) {
      inputs.push_back(hosted.inputs[i].get());
    }
  }
  return inputs;
}

void ControllerHost::set_reference_wait(std::int64_t wait_ns) {
  reference_wait_ns_ = wait_ns;
  for (auto& hosted : hosted_) {
    for (std::size_t i = 0; i < hosted->inputs.size(); ++i) {
      hosted->inputs[i]->set_wait(hosted->chained[i] ? 0 : wait_ns);
    }
  }
}

bool ControllerHost::wait_for_first_references(std::int64_t time_ns) {
  bool all = true;
  for (auto& hosted : hosted_) {
    for (std::size_t i = 0; i < hosted->inputs.size(); ++i) {
      if (!hosted->chained[i]) {
        all = hosted->inputs[i]->wait_for(time_ns, reference_wait_ns_) && all;
      }
    }
  }
  return all;
}

bool ControllerHost::references_ready(std::int64_t time_ns, bool first) const {
  if (reference_wait_ns_ <= 0) {
    return true;
  }
  for (const auto& hosted : hosted_) {
    for (std::size_t i = 0; i < hosted->inputs.size(); ++i) {
      if (!hosted->chained[i] && !hosted->inputs[i]->ready_for(time_ns, first)) {
        return false;
      }
    }
  }
  return true;
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
