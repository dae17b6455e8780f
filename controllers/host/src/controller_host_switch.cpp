// The controller host's switches and fallbacks (controller_host.hpp): which
// controllers are active on which joints, changed whole at a tick boundary;
// hold on the joints nobody commands.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "controller_host_hosted.hpp"

namespace wbi::controllers {

namespace {

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", t);
  return text;
}

template <class List, class Item>
bool contains(const List& list, const Item& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

}  // namespace

void ControllerHost::set_initial(const std::vector<std::string>& names) {
  std::vector<Hosted*> activate;
  for (const auto& name : names) {
    Hosted& hosted = find(name);
    if (!hosted.configured) {
      throw Error("controller '" + name + "' cannot start: " + hosted.configure_error);
    }
    if (&hosted != hold_ && !contains(activate, &hosted)) {
      activate.push_back(&hosted);
    }
  }
  if (activate.empty()) {  // hold alone: every joint held
    initial_.clear();
    return;
  }
  const PendingSwitch plan = plan_switch(activate, {}, false);
  if (!plan.result.text.empty()) {
    throw Error(plan.result.text);
  }
  initial_ = plan.activate;
}

// The first tick(s): the initial controllers, then hold on what they leave.
// False while there is no state to start from (tried again at the next tick).
bool ControllerHost::start(double time_s) {
  for (Hosted* hosted : initial_) {
    if (hosted->active) {
      continue;
    }
    try {
      if (!activate(*hosted)) {
        return false;
      }
    } catch (const TimeoutError&) {
      late_->add();  // a service it needs is late: tried again at the next tick
      return false;
    } catch (const std::exception& e) {
      fall_back(*hosted, std::string("threw in activate (") + e.what() + ")", time_s);
    }
  }
  rebuild_running();
  take_free_joints_to_hold();
  return !hold_pending_;  // hold starts with the rest: no blend from nothing
}

bool ControllerHost::activate(Hosted& hosted) {
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
  hosted.overruns_in_a_row = 0;
  hosted.ran = true;
  if (&hosted != hold_) {
    {
      std::lock_guard lock(switch_mutex_);
      hosted.active = true;
      active_.push_back(&hosted);
    }
    give_joints(hosted, &hosted);
  }
  return true;
}

void ControllerHost::deactivate(Hosted& hosted) {
  try {
    hosted.controller->deactivate();
  } catch (const std::exception& e) {
    report_.set_error("controller '" + hosted.name + "' threw in deactivate: " + e.what());
  }
  if (&hosted == hold_) {
    std::lock_guard lock(switch_mutex_);
    hold_active_ = false;
    return;
  }
  {
    std::lock_guard lock(switch_mutex_);
    hosted.active = false;
    active_.erase(std::remove(active_.begin(), active_.end(), &hosted), active_.end());
  }
  give_joints(hosted, nullptr);
}

// The joints of `hosted` that it owns (owner null) or frees (owner null) change
// hands: they blend from the last command (after the start) and count as switched.
void ControllerHost::give_joints(const Hosted& hosted, Hosted* owner) {
  for (const int j : hosted.joints) {
    auto& current = owner_[static_cast<std::size_t>(j)];
    if (owner ? current == owner : current != &hosted) {
      continue;
    }
    current = owner;
    switched_[static_cast<std::size_t>(j)] = 1;
    if (started_ && options_.blend_s > 0.0) {
      blend_pending_[static_cast<std::size_t>(j)] = 1;
    }
  }
}

void ControllerHost::take_free_joints_to_hold() {
  const bool any_free = contains(owner_, static_cast<Hosted*>(nullptr));
  hold_pending_ = false;
  if (!any_free) {
    if (hold_active_) {
      deactivate(*hold_);
      rebuild_running();
    }
    return;
  }
  if (!hold_ || !hold_->configured) {
    return;  // fall_back() said so; the robot's watchdog guards the free joints
  }
  try {
    // (Re)activated from the posture of now: a joint it takes is held where it is.
    if (!activate(*hold_)) {
      hold_pending_ = true;
      return;
    }
  } catch (const TimeoutError&) {
    late_->add();
    hold_pending_ = true;
    return;
  } catch (const std::exception& e) {
    {
      std::lock_guard lock(switch_mutex_);
      hold_->configured = false;
      hold_->configure_error = std::string("did not activate: ") + e.what();
    }
    report_.set_error("controller 'hold' did not activate (" + std::string(e.what()) +
                      "); the robot's watchdog takes over its joints");
    return;
  }
  if (started_ && options_.blend_s > 0.0) {
    for (std::size_t j = 0; j < owner_.size(); ++j) {
      blend_pending_[j] = blend_pending_[j] || owner_[j] == nullptr;
    }
  }
  {
    std::lock_guard lock(switch_mutex_);
    hold_active_ = true;
  }
  rebuild_running();
}

void ControllerHost::fall_back(Hosted& hosted, const std::string& reason, double time_s) {
  std::vector<Hosted*> out{&hosted};
  for (Hosted* planner : hosted.upstream) {  // planners that fed only it go with it
    const bool feeds_another =
        std::any_of(planner->downstream.begin(), planner->downstream.end(),
                    [&](const Hosted* other) { return other != &hosted && other->active; });
    if (planner->active && !feeds_another) {
      out.push_back(planner);
    }
  }
  for (Hosted* leaving : out) {
    if (is_running(*leaving)) {
      deactivate(*leaving);
    }
  }
  fallbacks_->add();
  std::string line = "controller '" + hosted.name + "' " + reason + ": fell back to '" +
                     kHoldController + "' at t = " + seconds(time_s);
  if (&hosted == hold_ || !hold_ || !hold_->configured) {
    line = "controller '" + hosted.name + "' " + reason + ": no controller active on its joints (" +
           (&hosted == hold_ ? "hold itself failed" : "no hold configured") +
           "); the robot's watchdog takes over";
    if (&hosted == hold_) {
      std::lock_guard lock(switch_mutex_);
      hosted.configured = false;  // not activated again in this run
      hosted.configure_error = "failed: " + reason;
    }
    rebuild_running();
  } else {
    take_free_joints_to_hold();
    if (hold_pending_) {
      line += "; hold did not activate yet (tried again each tick)";
    }
  }
  report_.set_error(line);
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
  events_.emit(EventSeverity::warning, EventKind::controller_fallback, line);
}

// Joints of the controllers active after a switch: pairwise disjoint.
std::string ControllerHost::check_joints(const std::vector<Hosted*>& after,
                                         const std::vector<Hosted*>& deactivate) const {
  for (std::size_t a = 0; a < after.size(); ++a) {
    for (std::size_t b = a + 1; b < after.size(); ++b) {
      if (!after[a]->shares_joints(*after[b])) {
        continue;
      }
      const Hosted* staying = after[a]->active && !contains(deactivate, after[a])   ? after[a]
                              : after[b]->active && !contains(deactivate, after[b]) ? after[b]
                                                                                    : nullptr;
      std::string shared;
      for (const int j : after[a]->joints) {
        if (contains(after[b]->joints, j)) {
          shared += (shared.empty() ? "" : ", ") + robot_.joint_list()[static_cast<std::size_t>(j)];
        }
      }
      if (staying) {
        const Hosted* coming = staying == after[a] ? after[b] : after[a];
        return "'" + staying->name + "' is active on the same joints as '" + coming->name + "' (" +
               shared + "): deactivate it in the same switch (--deactivate " + staying->name + ")";
      }
      return "'" + after[a]->name + "' and '" + after[b]->name + "' would both command " + shared;
    }
  }
  return "";
}

ControllerHost::PendingSwitch ControllerHost::plan_switch(const std::vector<Hosted*>& activate,
                                                          const std::vector<Hosted*>& deactivate,
                                                          bool to_hold) const {
  PendingSwitch plan;
  const auto refuse = [&](std::string text) {
    plan.result.text = std::move(text);
    return plan;
  };
  std::string active_names;
  for (const Hosted* hosted : active_) {
    active_names += (active_names.empty() ? "" : ", ") + hosted->name;
  }
  if (hold_active_) {
    active_names += (active_names.empty() ? "" : ", ") + std::string(kHoldController);
  }
  for (const Hosted* off : deactivate) {
    if (!is_running(*off)) {
      return refuse("'" + off->name + "' is not active (active: " +
                    (active_names.empty() ? std::string("none") : active_names) + ")");
    }
  }
  std::vector<Hosted*> on;
  for (Hosted* coming : activate) {
    if (!coming->configured) {
      return refuse("'" + coming->name + "' cannot be activated: " + coming->configure_error);
    }
    if (coming->active && !contains(deactivate, coming)) {
      return refuse("'" + coming->name + "' is already active");
    }
    on.push_back(coming);
  }
  // The planners that feed what is activated come with it.
  for (std::size_t i = 0; i < on.size(); ++i) {
    for (Hosted* planner : on[i]->upstream) {
      if (contains(deactivate, planner)) {
        return refuse("'" + planner->name + "' feeds '" + on[i]->name +
                      "': it stays active while that is");
      }
      if (!planner->active && !contains(on, planner)) {
        if (!planner->configured) {
          return refuse("'" + planner->name + "', which feeds '" + on[i]->name +
                        "', cannot be activated: " + planner->configure_error);
        }
        on.push_back(planner);
      }
    }
  }
  std::vector<Hosted*> off;
  for (Hosted* leaving : deactivate) {
    if (leaving != hold_) {
      off.push_back(leaving);
    }
  }
  if (on.empty() && off.empty()) {
    if (to_hold) {
      return refuse("nothing to hold: name the controllers whose joints hold takes (--deactivate " +
                    (active_.empty() ? std::string("...: none is active") : active_.front()->name) +
                    ")");
    }
    return refuse("nothing to switch: name controllers to activate or deactivate");
  }
  std::vector<Hosted*> after;
  for (Hosted* hosted : active_) {
    if (!contains(off, hosted)) {
      after.push_back(hosted);
    }
  }
  after.insert(after.end(), on.begin(), on.end());
  // Planners whose every fed controller leaves go with them.
  for (Hosted* planner : active_) {
    const bool fed = std::any_of(planner->downstream.begin(), planner->downstream.end(),
                                 [&](const Hosted* d) { return contains(after, d); });
    if (!planner->downstream.empty() && !fed && !contains(off, planner)) {
      off.push_back(planner);
      after.erase(std::remove(after.begin(), after.end(), planner), after.end());
    }
  }
  if (std::string conflict = check_joints(after, off); !conflict.empty()) {
    return refuse(conflict);
  }
  plan.activate = std::move(on);
  plan.deactivate = std::move(off);
  return plan;
}

SwitchResult ControllerHost::request_switch(const std::vector<std::string>& activate,
                                            const std::vector<std::string>& deactivate) {
  SwitchResult refused;
  const auto refuse = [&](std::string text) {
    refused_->add();
    refused.text = std::move(text);
    return refused;
  };
  std::vector<Hosted*> on, off;
  bool to_hold = false;
  try {
    for (const auto& name : activate) {
      Hosted* hosted = &find(name);
      to_hold = to_hold || hosted == hold_;
      if (hosted != hold_ && !contains(on, hosted)) {
        on.push_back(hosted);
      }
    }
    for (const auto& name : deactivate) {
      Hosted* hosted = &find(name);
      if (!contains(off, hosted)) {
        off.push_back(hosted);
      }
    }
  } catch (const Error& e) {
    return refuse(e.what());
  }
  // Under the lock: plan_switch reads what the loop changes under it.
  std::unique_lock lock(switch_mutex_);
  if (switch_.pending) {
    return refuse("another switch is pending");
  }
  PendingSwitch plan = plan_switch(on, off, to_hold);
  if (!plan.result.text.empty()) {
    return refuse(plan.result.text);
  }
  switch_ = std::move(plan);
  switch_.pending = true;
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

std::string ControllerHost::schedule_switch(const std::string& activate, const std::string& from) {
  Hosted* to = nullptr;
  Hosted* named = nullptr;
  try {
    to = &find(activate);
    named = from.empty() ? nullptr : &find(from);
  } catch (const Error& e) {
    refused_->add();
    return e.what();
  }
  // It takes its joints from the controllers on them (or from `from`); hold
  // takes every joint (or from's).
  std::vector<Hosted*> off;
  for (Hosted* hosted : active_) {
    const bool takes =
        named ? hosted == named : hosted != to && (to == hold_ || hosted->shares_joints(*to));
    if (takes) {
      off.push_back(hosted);
    }
  }
  if (named && off.empty()) {
    refused_->add();
    return "'" + from + "' is not active";
  }
  if (to == hold_ && off.empty()) {
    refused_->add();
    return "'hold' is already active";
  }
  PendingSwitch plan = to == hold_ ? plan_switch({}, off, true) : plan_switch({to}, off, false);
  std::lock_guard lock(switch_mutex_);
  if (switch_.pending) {
    plan.result.text = "another switch is pending";
  }
  if (!plan.result.text.empty()) {
    refused_->add();
    return plan.result.text;
  }
  switch_ = std::move(plan);
  switch_.pending = true;
  switch_requested_.store(true, std::memory_order_release);
  switches_->add();  // applied by the next tick
  return "";
}

bool ControllerHost::apply_switch(double time_s) {
  std::unique_lock lock(switch_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !switch_.pending) {
    return false;  // the requester holds the lock for a moment: at the next tick
  }
  const std::vector<Hosted*> off = switch_.deactivate;
  const std::vector<Hosted*> on = switch_.activate;
  lock.unlock();
  std::fill(switched_.begin(), switched_.end(), 0);
  // Joints hold had that an activated controller takes: hold gives them.
  const bool hold_gives = hold_active_ && std::any_of(on.begin(), on.end(), [&](const Hosted* h) {
                            return std::any_of(h->joints.begin(), h->joints.end(), [&](int j) {
                              return owner_[static_cast<std::size_t>(j)] == nullptr;
                            });
                          });
  for (Hosted* leaving : off) {
    deactivate(*leaving);
  }
  std::string failure;
  const Hosted* failed = nullptr;
  for (Hosted* coming : on) {
    try {
      if (!activate(*coming)) {
        failure = "no fresh state to activate it from";
      }
    } catch (const std::exception& e) {
      failure = e.what();
    }
    if (!failure.empty()) {
      failed = coming;
      break;
    }
  }
  if (failed) {  // whole or not at all: what came goes again
    for (Hosted* coming : on) {
      if (coming->active) {
        deactivate(*coming);
      }
    }
  }
  rebuild_running();
  take_free_joints_to_hold();
  const bool hold_takes = contains(owner_, static_cast<Hosted*>(nullptr));
  const auto names = [](const std::vector<Hosted*>& list, bool with_hold) {
    std::string text;
    for (const Hosted* hosted : list) {
      text += (text.empty() ? "" : ", ") + hosted->name;
    }
    if (with_hold) {
      text += (text.empty() ? "" : ", ") + std::string(kHoldController);
    }
    return text.empty() ? std::string("none") : text;
  };
  const std::string from = names(off, hold_gives);
  lock.lock();
  switch_.result.time_s = time_s;
  switch_.result.from = from;
  switch_.result.to = names(failed ? std::vector<Hosted*>{} : on, hold_takes && !failed);
  if (!failed) {
    switch_.result.done = true;
    switch_.result.text = from + " → " + switch_.result.to + " at t = " + seconds(time_s);
  } else {
    switch_.result.to = names({}, true);
    switch_.result.text = "'" + failed->name + "' did not activate: " + failure;
  }
  lock.unlock();
  if (failed && !off.empty()) {
    fallbacks_->add();
    const std::string line = "controller '" + off.front()->name + "' was switched out but '" +
                             failed->name + "' did not activate (" + failure + "): fell back to '" +
                             kHoldController + "' at t = " + seconds(time_s);
    report_.set_error(line);
    std::fprintf(stderr, "%s\n", line.c_str());
    events_.emit(EventSeverity::warning, EventKind::controller_fallback, line);
  }
  return true;
}

// After the switch tick's command: its step, then the requester is answered.
void ControllerHost::finish_switch() {
  std::unique_lock lock(switch_mutex_);
  if (!switch_.pending) {
    return;
  }
  if (switch_.result.done && !running_.empty()) {
    // The first command sent after the switch against the last one before it,
    // over every joint, the joints that changed hands, and the others.
    double before = 0.0, step = 0.0, before_switched = 0.0, step_switched = 0.0;
    for (int j = 0; j < last_command_.size(); ++j) {
      const double b = before_switch_[j] * before_switch_[j];
      const double d =
          (last_command_[j] - before_switch_[j]) * (last_command_[j] - before_switch_[j]);
      before += b;
      step += d;
      if (switched_[static_cast<std::size_t>(j)]) {
        before_switched += b;
        step_switched += d;
      }
    }
    const auto ratio = [](double num, double den) {
      return den > 0.0 ? std::sqrt(num) / std::sqrt(den) : 0.0;
    };
    switch_.result.torque_step = ratio(step, before);
    switch_.result.torque_step_switched = ratio(step_switched, before_switched);
    switch_.result.torque_step_others = ratio(step - step_switched, before - before_switched);
    const double before_norm = std::sqrt(before);
    char text[160];
    std::snprintf(text, sizeof text, "; torque step %.2f %% of the %.3g N m applied",
                  100.0 * switch_.result.torque_step, before_norm);
    switch_.result.text += text;
    if (before_switched < before) {  // some joints kept their controller
      std::snprintf(text, sizeof text,
                    " (the joints that changed hands %.2f %%; the others, their own controllers' "
                    "change, %.2f %%)",
                    100.0 * switch_.result.torque_step_switched,
                    100.0 * switch_.result.torque_step_others);
      switch_.result.text += text;
    }
    switch_.result.torque_before = before_norm;
    switch_.result.largest_change_before = before_norm > 0.0 ? largest_change_ / before_norm : 0.0;
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

}  // namespace wbi::controllers
