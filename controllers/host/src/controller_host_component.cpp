#include "wbi/controllers/controller_host_component.hpp"

#include <array>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>

#include <wbi/controllers/controller_host.hpp>
#include <wbi/controllers/interface_options.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/runtime/process_exit.hpp>
#include <wbi/runtime/producer_counters.hpp>

#include "host_service.hpp"

namespace wbi::controllers {

namespace {

// Reads a controller's declared parameters from its map in the deploy file.
void read_declared(const runtime::Parameters& parameters, ParameterTable& table) {
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParameterSpec& spec = table.spec(i);
    if (spec.text) {
      table.set_text(i, parameters.get<std::string>(spec.name, spec.text_default));
      continue;
    }
    const bool required = spec.default_value.empty() && !spec.optional;
    if (!parameters.has(spec.name)) {
      if (required) {
        throw runtime::ParameterError(parameters.where() + ": missing parameter '" + spec.name +
                                      "' (" + spec.help + ")");
      }
      continue;
    }
    std::vector<double> values;
    if (spec.size == 1) {
      values.push_back(parameters.require<double>(spec.name));
    } else {
      values = parameters.require<std::vector<double>>(spec.name);
    }
    if (const std::string problem = table.check(i, values, false); !problem.empty()) {
      throw runtime::ParameterError(parameters.where(spec.name) + ": " + problem);
    }
    table.set(i, values);
  }
}

class ControllerHostComponent final : public runtime::Component {
 public:
  // single: the type of the one controller a `<type>` component hosts; empty
  // for a controller_host, whose controllers come from its `controllers:` map.
  ControllerHostComponent(std::shared_ptr<const ControllerRegistry> types, std::string single)
      : types_(std::move(types)), single_(std::move(single)) {}

  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    DdsInterfaceOptions options = read_interface_options(parameters, context);
    wait_for_state_ = parameters.get<bool>("wait_for_state", false);
    // The cycle on the DDS thread that delivers the state, not a thread of our
    // own woken by it. Not with a remote model: its reply comes on that thread.
    cycle_on_state_thread_ = wait_for_state_ &&
                             options.model_source == DdsInterfaceOptions::ModelSource::local &&
                             parameters.get<bool>("cycle_on_state_thread", true);
    options.blocking_read_timeout = std::chrono::milliseconds(
        static_cast<std::int64_t>(parameters.get<double>("state_timeout_s", 0.005) * 1000));
    const auto joints = parameters.require<std::vector<std::string>>("joints");
    const double init_timeout_s = parameters.get<double>("init_timeout_s", 30.0);
    progress_period_s_ = parameters.get<double>("progress_period_s", 1.0);
    ControllerHost::Options host_options;
    host_options.overrun_limit = parameters.get<int>("overrun_limit", host_options.overrun_limit);
    if (host_options.overrun_limit < 0) {
      throw runtime::ParameterError(
          parameters.where("overrun_limit") +
          ": overrun_limit must be >= 0 (0: never fall back on overruns)");
    }
    host_options.blend_s = parameters.get<double>("blend_s", host_options.blend_s);
    if (!(host_options.blend_s >= 0.0)) {
      throw runtime::ParameterError(parameters.where("blend_s") + ": blend_s must be >= 0 s");
    }
    exit_after_s_ = parameters.get<double>("exit_after_s", 0.0);
    switch_at_s_ = parameters.get<std::vector<double>>("switch_at_s", {});
    switch_to_ = parameters.get<std::vector<std::string>>("switch_to", {});
    if (switch_at_s_.size() != switch_to_.size()) {
      throw runtime::ParameterError(parameters.where("switch_to") + ": switch_at_s has " +
                                    std::to_string(switch_at_s_.size()) + " times, switch_to " +
                                    std::to_string(switch_to_.size()) + " controllers");
    }
    // Whose joints each scheduled switch takes ("": the controllers on them).
    switch_from_ = parameters.get<std::vector<std::string>>(
        "switch_from", std::vector<std::string>(switch_to_.size()));
    if (switch_from_.size() != switch_to_.size()) {
      throw runtime::ParameterError(
          parameters.where("switch_from") + ": switch_to has " + std::to_string(switch_to_.size()) +
          " controllers, switch_from " + std::to_string(switch_from_.size()));
    }
    for (std::size_t i = 1; i < switch_at_s_.size(); ++i) {
      if (!(switch_at_s_[i] > switch_at_s_[i - 1])) {
        throw runtime::ParameterError(parameters.where("switch_at_s") +
                                      ": switch_at_s must increase");
      }
    }

    // A new estimator is a rebound of the state stream (wbi/dds/producers.hpp),
    // said before its first sample is taken (and a PRODUCER_RESTARTED event).
    new_estimators_ = &report().counter("new_estimators");
    std::string state_topic = dds::topics::state(options.robot);
    std::string quoted = "'" + state_topic + "'";  // as the rebound's line quotes it
    options.on_producer_event = [count = runtime::count_producer_events(report()),
                                 state = std::move(quoted), topic = std::move(state_topic),
                                 this](const dds::ProducerEvent& event) {
      count(event);
      if (event.kind == dds::ProducerEvent::Kind::rebound &&
          event.text.find(state) != std::string_view::npos && host_) {
        new_estimators_->add();
        host_->notify_state_source_changed();
        events().emit(EventSeverity::info, EventKind::producer_restarted, event.text, topic);
      }
    };
    robot_ = make_dds_interface(options);
    robot_->add_joints(joints);
    robot_->init(std::chrono::milliseconds(static_cast<std::int64_t>(init_timeout_s * 1000)));
    // On the clock in lockstep, a cycle whose newest state a cycle answered
    // already is skipped. The robot sends the next state only once it has
    // this one's commands, so a cycle that answers a state reads that one
    // throughout: its time's read and its controllers'. Else the next state
    // could come between them, and a tick would mix two, run to run.
    skip_answered_states_ = !wait_for_state_ && robot_in_lockstep(*robot_);
    host_.emplace(*robot_, report(), events(), host_options);

    std::vector<std::string> active{kHoldController};
    if (!single_.empty()) {
      // Named after the component: its signals, references and parameters
      // are the instance's (wbi/<robot>/references/<instance>/…).
      add(context.instance, single_, parameters);
      active = {context.instance};
    } else {
      const runtime::Parameters controllers = parameters.child("controllers", "controllers");
      std::vector<std::pair<std::string, runtime::Parameters>> owns;
      for (const auto& name : controllers.keys()) {
        owns.emplace_back(name, controllers.child(name, "controller '" + name + "'"));
        add(name, owns.back().second.get<std::string>("type", name), owns.back().second);
      }
      // Once all are in: a planner may be listed after the controller it feeds.
      for (const auto& [name, own] : owns) {
        if (own.has("inputs")) {
          const runtime::Parameters inputs = own.child("inputs", "inputs");
          chain(name, inputs);
          inputs.reject_unknown();
        }
        own.reject_unknown();
      }
      active = names(parameters, "active", active);
    }
    if (!host_->list().empty() && !has(kHoldController)) {
      add(kHoldController, kHoldController, runtime::Parameters());
    }
    try {
      host_->set_initial(active);
    } catch (const Error& e) {
      throw runtime::ParameterError(parameters.where("active") + ": " + e.what());
    }
    for (const auto& name : switch_from_) {
      if (!name.empty() && !has(name)) {
        throw runtime::ParameterError(parameters.where("switch_from") + ": no controller '" + name +
                                      "' among this host's");
      }
    }
    for (const auto& name : switch_to_) {
      if (!has(name)) {
        throw runtime::ParameterError(parameters.where("switch_to") + ": no controller '" + name +
                                      "' among this host's");
      }
    }
    newest_q_.setZero(robot_->dofs());
    if (parameters.get<bool>("signals", true)) {
      signals_publisher_ = std::make_unique<dds::Publisher<msg::Signals>>(
          *context.participant, dds::topics::signals(options.robot, context.instance),
          dds::qos::kStream);
      signals_.header().robot(options.robot);
      signals_.source(context.instance);
      signals_.names().reserve(msg::MAX_SIGNALS);
      signals_.values().reserve(msg::MAX_SIGNALS);
    }
    reference_wait_ns_ =
        static_cast<std::int64_t>(parameters.get<double>("reference_wait_s", 0.0) * 1e9);
    if (reference_wait_ns_ < 0) {
      throw runtime::ParameterError(parameters.where("reference_wait_s") +
                                    ": reference_wait_s must be >= 0 s (0: never wait)");
    }
    if (1e-9 * static_cast<double>(reference_wait_ns_) >= options.max_age_s) {
      // The state a tick answers ages while it waits: waited for that long,
      // it is refused as stale, and a lockstep robot waits for that tick forever.
      throw runtime::ParameterError(parameters.where("reference_wait_s") +
                                    ": reference_wait_s must be shorter than max_age_s (" +
                                    std::to_string(options.max_age_s) +
                                    " s): a state waited for that long is too old to answer");
    }
    host_->set_reference_wait(reference_wait_ns_);
    subscribe_references(*context.participant, options.robot);
    if (cycle_on_state_thread_) {
      set_state_callback(*robot_, [this] { run_event_cycle(); });
    }
    service_.emplace(*context.participant, options.robot, context.instance, *host_);
    service_->publish_parameters();
  }

  void on_activate() override {
    start_ns_ = -1;
    next_progress_s_ = 0.0;
  }

  // Event-driven (wait_for_state): one cycle per state estimate, the newest
  // one this host has not answered yet. It may be there already (the one
  // init() saw, one that came during the last cycle): then at once, whatever
  // the controllers read meanwhile (a read of the same kind from configure or
  // activate would make a blocking read wait for the next estimate, which a
  // lockstep robot sends only once this one is answered). With the cycle on
  // the state's thread only the runner's watchdog calls it: a state no
  // arrival answered for ten periods (its reference points are late: the
  // tick waits for them, on the watchdog's thread).
  bool event_driven() const override { return wait_for_state_; }
  bool wait_for_event(std::int64_t /*timeout_ns*/) override {
    try {
      if (const auto newest = newest_state(); newest && !answered(*newest)) {
        return true;
      }  // none fresh, or answered: wait for the next
      if (cycle_on_state_thread_) {
        return false;  // the runner's watchdog: arrivals run the cycles, no waiting here
      }
      robot_->read_estimates(EstimateKind::joint_position, newest_q_, ReadMode::blocking);
      return true;
    } catch (const TimeoutError&) {
      ++event_timeouts_;  // no new estimate within state_timeout_s
    } catch (const StaleDataError&) {
      ++event_timeouts_;
    }
    return false;
  }

  bool cycles_on_event_thread() const override { return cycle_on_state_thread_; }
  void set_event_cycle(runtime::EventCycle* cycle) override {
    std::lock_guard lock(event_cycle_mutex_);  // after a call in progress
    event_cycle_ = cycle;
  }
  // A cycle is due for the newest state when no cycle answered it yet and,
  // in lockstep with reference generators, their points for its time are in
  // (else the tick would wait for them, on the thread that must bring them).
  bool event_ready() override {
    const auto newest = newest_state();
    if (!newest || answered(*newest)) {
      return false;
    }
    return reference_wait_ns_ <= 0 ||
           host_->references_ready(newest->source_ns, start_ns_ < 0 || !references_started_);
  }

  void update(std::int64_t /*time_ns*/, std::int64_t period_ns) override {
    if (skip_answered_states_) {
      if (const auto newest = newest_state(); newest && answered(*newest)) {
        return;
      }
    }
    const double period_s = 1e-9 * static_cast<double>(period_ns);
    const double t = robot_time(period_s);
    if (next_switch_ < switch_at_s_.size() && t >= switch_at_s_[next_switch_]) {
      const std::string refused =
          host_->schedule_switch(switch_to_[next_switch_], switch_from_[next_switch_]);
      if (!refused.empty()) {
        std::printf("switch at t = %.3f s refused: %s\n", t, refused.c_str());
      }
      ++next_switch_;
    }
    if (reference_wait_ns_ > 0 && start_ns_ >= 0 && !references_started_) {
      references_started_ = true;
      host_->wait_for_first_references(state_stamp_ns_);
    }
    const std::uint64_t switches_before = host_->switches_ended();
    host_->tick(t, period_s);
    if (host_->switches_ended() != switches_before) {
      std::printf("switch: %s\n", host_->last_switch().text.c_str());
      std::fflush(stdout);
    }
    if (host_->switches_settled() != switches_settled_) {
      switches_settled_ = host_->switches_settled();
      const SwitchResult& settled = host_->last_settled();
      std::printf(
          "switch %s → %s settled: largest change between two commands %.2f %% of the "
          "%.3g N m applied over %.2f s (before the switch: %.2f %%)\n",
          settled.from.c_str(), settled.to.c_str(), 100.0 * settled.largest_change,
          settled.torque_before, settled.settled_after_s, 100.0 * settled.largest_change_before);
      std::fflush(stdout);
    }
    if (exit_after_s_ > 0.0 && t >= exit_after_s_ && !exit_requested_) {
      end_run();
    }
    Controller* active = host_->active_controller();
    if (active) {
      publish_signals(*active);
    }
    for (Controller* running : host_->active_controllers()) {
      if (running->finished() && !exit_requested_) {
        end_run();
      }
    }
    if (active && progress_period_s_ > 0 && t >= next_progress_s_) {
      next_progress_s_ += progress_period_s_;
      active->progress(progress_line_.data(), progress_line_.size());
      std::printf("t = %6.2f s  %s\n", t, progress_line_.data());
      std::fflush(stdout);
    }
  }

  void on_shutdown() override {
    if (robot_ && cycle_on_state_thread_) {
      set_state_callback(*robot_, nullptr);
    }
    if (host_) {
      if (!exit_requested_) {
        take_run_figures();
      }
      std::printf("stale cycles: %llu\n", static_cast<unsigned long long>(stale_at_end_));
      if (!summary_at_end_.empty()) {
        std::printf("%s\n", summary_at_end_.c_str());
      }
      std::fflush(stdout);
    }
    service_.reset();
    reference_readers_.clear();
    signals_publisher_.reset();
    host_.reset();
    if (robot_) {
      robot_->close();
    }
  }

 private:
  // The run is over: end the hosting process (wbi_host shuts the components
  // down, so the summary is printed), and `wbi launch` with it; failed when a
  // controller's figures are computed over nothing.
  void end_run() {
    exit_requested_ = true;
    take_run_figures();
    int code = 0;
    for (Controller* running : host_->active_controllers()) {
      if (const std::string why = running->figures_missing(); !why.empty()) {
        std::fprintf(stderr, "the run failed: %s\n", why.c_str());
        std::fflush(stderr);
        code = runtime::kExitRunFailed;
      }
    }
    runtime::request_process_exit(code);
  }

  // The figures printed at shutdown, taken when the run ends: the ticks the
  // controllers answer while the process shuts down (a lockstep robot steps
  // on meanwhile) are as many as the machine's timing allows, and would reach
  // them.
  void take_run_figures() {
    stale_at_end_ = stale_cycles() + event_timeouts_;
    summary_at_end_ = host_->summary();
  }

  // A state, or a reference point, arrived (on its DDS thread): the runner's
  // cycle, here, when it completes a tick's inputs. An arrival nested in a
  // cycle on this thread (Fast DDS delivers in the writer's thread within a
  // process) is left to the runner's watchdog.
  void run_event_cycle() {
    static thread_local bool in_cycle = false;
    if (in_cycle) {
      return;
    }
    in_cycle = true;
    {
      std::lock_guard lock(event_cycle_mutex_);
      if (event_cycle_ != nullptr) {
        event_cycle_->run();
      }
    }
    in_cycle = false;
  }

  // The newest state estimate's stamp; nullopt when none is fresh.
  std::optional<Stamp> newest_state() {
    try {
      return robot_->read_estimates(EstimateKind::joint_position, newest_q_, ReadMode::latest);
    } catch (const StaleDataError&) {
      return std::nullopt;
    }
  }
  bool answered(const Stamp& state) const { return has_answered_ && state.seq == answered_seq_; }

  // The robot's time since the first tick: the newest state's source stamp
  // (the simulation's time in lockstep), so that times in the deploy file
  // (switch_at_s, transitions) mean the same in every run. Without a fresh
  // state, one period on.
  double robot_time(double period_s) {
    try {
      const Stamp stamp = robot_->read_base_pose(base_pose_, ReadMode::latest);
      if (start_ns_ < 0) {
        start_ns_ = stamp.source_ns;
      }
      state_stamp_ns_ = stamp.source_ns;
      answered_seq_ = stamp.seq;
      has_answered_ = true;
      last_time_s_ = 1e-9 * static_cast<double>(stamp.source_ns - start_ns_);
    } catch (const StaleDataError&) {
      last_time_s_ += period_s;
    }
    return last_time_s_;
  }

  // The active controller's signals, once per state it answered; the names
  // are set again when the active controller changed (the only allocation).
  void publish_signals(const Controller& active) {
    const auto values = active.signals();
    const std::int64_t stamp = active.signals_stamp_ns();
    if (!signals_publisher_ || values.empty() || values.size() > msg::MAX_SIGNALS ||
        (&active == signals_of_ && stamp == signals_.header().stamp_ns())) {
      return;
    }
    if (&active != signals_of_) {
      signals_of_ = &active;
      signals_.names().clear();
      for (const auto& name : active.signal_names()) {
        signals_.names().emplace_back(name);
      }
    }
    signals_.values().assign(values.begin(), values.end());
    signals_.header().stamp_ns(stamp);
    signals_.header().seq(signals_seq_++);
    signals_publisher_->publish(signals_);
  }

  void add(const std::string& name, const std::string& type,
           const runtime::Parameters& parameters) {
    std::unique_ptr<Controller> controller;
    try {
      // hold is the host's own; every other type comes from the plugins.
      controller = type == kHoldController ? make_hold_controller() : types_->create(type);
    } catch (const std::invalid_argument& e) {
      throw runtime::ParameterError(parameters.where("type") + ": " + e.what());
    }
    ParameterTable& table = host_->add(name, type, std::move(controller));
    // In a host's `controllers:` map, the joints it commands (a subset of the
    // host's; none for a planner); one controller of its own type commands them all.
    if (single_.empty() && parameters.has("joints")) {
      try {
        host_->set_joints(name, parameters.require<std::vector<std::string>>("joints"));
      } catch (const Error& e) {
        throw runtime::ParameterError(parameters.where("joints") + ": " + e.what());
      }
    }
    read_declared(parameters, table);
    try {
      host_->configure(name);
    } catch (const Error& e) {
      throw runtime::ParameterError(parameters.where() + ": " + e.what());
    }
  }

  // `inputs: {INPUT: PLANNER[/OUTPUT]}` of controller `name`: each input fed
  // in the same tick by a planner of this host (its output of the same name
  // unless named), not from the input's topic.
  void chain(const std::string& name, const runtime::Parameters& inputs) {
    for (const auto& input : inputs.keys()) {
      const std::string source = inputs.require<std::string>(input);
      const auto slash = source.find('/');
      const std::string planner = source.substr(0, slash);
      const std::string output = slash == std::string::npos ? input : source.substr(slash + 1);
      try {
        host_->chain(name, input, planner, output);
      } catch (const Error& e) {
        throw runtime::ParameterError(inputs.where(input) + ": " + e.what());
      }
    }
  }

  // A name or a list of names.
  static std::vector<std::string> names(const runtime::Parameters& parameters,
                                        const std::string& key,
                                        const std::vector<std::string>& fallback) {
    if (!parameters.has(key)) {
      return fallback;
    }
    try {
      return {parameters.require<std::string>(key)};
    } catch (const runtime::ParameterError&) {
      return parameters.require<std::vector<std::string>>(key);
    }
  }

  // One reader per declared reference input of every hosted controller,
  // feeding the host's input as points arrive (on the reader's thread).
  void subscribe_references(dds::Participant& participant, const std::string& robot) {
    for (const auto& info : host_->list()) {
      for (ReferenceInput* input : host_->references(info.name)) {
        const std::string topic = dds::topics::reference(robot, info.name, input->spec().name);
        reference_readers_.push_back(std::make_unique<dds::Subscriber<msg::TrajectoryPoint>>(
            participant, topic, dds::qos::kCommand,
            [input, this](const msg::TrajectoryPoint& sample, const dds::detail::SampleInfo&) {
              input->push(to_point(sample));
              if (cycle_on_state_thread_ && reference_wait_ns_ > 0) {
                run_event_cycle();  // the point a tick waits for may be the last input
              }
            }));
      }
    }
  }

  static TrajectoryPoint to_point(const msg::TrajectoryPoint& sample) {
    TrajectoryPoint point;
    point.stamp_ns = sample.header().stamp_ns();
    point.seq = sample.header().seq();
    const auto& x = sample.position();
    point.size = static_cast<int>(x.size());
    const auto copy = [&](const std::vector<double>& from, auto& to) {
      if (from.size() == x.size()) {  // else empty (zero) or malformed: zero
        std::copy(from.begin(), from.end(), to.begin());
      }
    };
    copy(x, point.position);
    copy(sample.velocity(), point.velocity);
    copy(sample.acceleration(), point.acceleration);
    return point;
  }

  bool has(const std::string& name) const {
    for (const auto& info : host_->list()) {
      if (info.name == name) {
        return true;
      }
    }
    return false;
  }

  std::uint64_t stale_cycles() const {
    for (std::size_t i = 0; i < report().counter_count(); ++i) {
      if (report().counter_name(i) == "stale_cycles") {
        return report().counter_value(i);
      }
    }
    return 0;
  }

  std::shared_ptr<const ControllerRegistry> types_;
  std::string single_;
  std::unique_ptr<WholeBodyInterface> robot_;
  std::optional<ControllerHost> host_;
  std::optional<HostService> service_;  // after host_: destroyed first
  double progress_period_s_ = 1.0;
  bool wait_for_state_ = false;
  bool cycle_on_state_thread_ = false;  // runtime::Component::cycles_on_event_thread
  bool skip_answered_states_ = false;   // on the clock, in lockstep
  std::mutex event_cycle_mutex_;        // guards event_cycle_; held while it runs
  runtime::EventCycle* event_cycle_ = nullptr;
  Eigen::VectorXd newest_q_;    // newest_state's read (the tick reads the same sample again)
  std::int64_t start_ns_ = -1;  // source stamp of the first state
  double last_time_s_ = 0.0, next_progress_s_ = 0.0;
  Transform base_pose_ = Transform::Identity();
  double exit_after_s_ = 0.0;
  std::vector<double> switch_at_s_;
  std::vector<std::string> switch_to_, switch_from_;
  std::size_t next_switch_ = 0;
  std::uint64_t switches_settled_ = 0;
  std::uint64_t event_timeouts_ = 0;
  std::array<char, 160> progress_line_{};
  bool exit_requested_ = false;     // by the host's exit_after_s or a finished controller
  std::uint64_t stale_at_end_ = 0;  // take_run_figures
  std::string summary_at_end_;
  runtime::StatusCounter* new_estimators_ = nullptr;
  std::unique_ptr<dds::Publisher<msg::Signals>> signals_publisher_;
  std::vector<std::unique_ptr<dds::Subscriber<msg::TrajectoryPoint>>> reference_readers_;
  std::int64_t reference_wait_ns_ = 0;  // lockstep: wait this long for a reference's point
  std::int64_t state_stamp_ns_ = 0;     // source stamp of the newest state
  std::uint64_t answered_seq_ = 0;      // sequence number of the state the last cycle answered
  bool has_answered_ = false;
  bool references_started_ = false;  // the first tick waited for the generators
  msg::Signals signals_;
  const Controller* signals_of_ = nullptr;  // whose names signals_ carries
  std::uint64_t signals_seq_ = 0;
};

}  // namespace

void register_components(runtime::Registry& registry,
                         std::shared_ptr<const ControllerRegistry> types) {
  registry.add(
      "controller_host", [types] { return std::make_unique<ControllerHostComponent>(types, ""); },
      "runs controllers on a robot's joints: lifecycle, switching, live parameters, hold");
}

void register_single_controller_hosts(runtime::Registry& registry,
                                      std::shared_ptr<const ControllerRegistry> types) {
  for (const auto& type : types->names()) {
    if (registry.contains(type)) {
      continue;  // a component type of that name (e.g. its own host type): the map form only
    }
    registry.set_provider(types->provider(type));
    registry.add(
        type, [types, type] { return std::make_unique<ControllerHostComponent>(types, type); },
        types->description(type) + " (a controller host with this one controller)");
  }
}

}  // namespace wbi::controllers
