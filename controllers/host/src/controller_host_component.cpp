#include "wbi/controllers/controller_host_component.hpp"

#include <array>
#include <cstdio>
#include <memory>
#include <optional>

#include <wbi/controllers/controller_host.hpp>
#include <wbi/controllers/controller_types.hpp>
#include <wbi/controllers/interface_options.hpp>
#include <wbi/dds/publisher.hpp>
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
  explicit ControllerHostComponent(std::string single) : single_(std::move(single)) {}

  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    DdsInterfaceOptions options = read_interface_options(parameters, context);
    wait_for_state_ = parameters.get<bool>("wait_for_state", false);
    options.blocking_read_timeout = std::chrono::milliseconds(
        static_cast<std::int64_t>(parameters.get<double>("state_timeout_s", 0.005) * 1000));
    const auto joints = parameters.require<std::vector<std::string>>("joints");
    const double init_timeout_s = parameters.get<double>("init_timeout_s", 30.0);
    progress_period_s_ = parameters.get<double>("progress_period_s", 1.0);
    ControllerHost::Options host_options;
    host_options.overrun_limit = parameters.get<int>("overrun_limit", host_options.overrun_limit);

    // A new estimator is a rebound of the state stream (wbi/dds/producers.hpp),
    // said before its first sample is taken.
    new_estimators_ = &report().counter("new_estimators");
    std::string state_topic = "'";  // as the rebound's line quotes it
    state_topic += dds::topics::state(options.robot);
    state_topic += '\'';
    options.on_producer_event = [count = runtime::count_producer_events(report()),
                                 state = std::move(state_topic),
                                 this](const dds::ProducerEvent& event) {
      count(event);
      if (event.kind == dds::ProducerEvent::Kind::rebound &&
          event.text.find(state) != std::string_view::npos && host_) {
        new_estimators_->add();
        host_->notify_state_source_changed();
      }
    };
    robot_ = make_dds_interface(options);
    robot_->add_joints(joints);
    robot_->init(std::chrono::milliseconds(static_cast<std::int64_t>(init_timeout_s * 1000)));
    host_.emplace(*robot_, report(), host_options);

    std::string active = kHoldController;
    if (!single_.empty()) {
      add(single_, single_, parameters);
      active = single_;
    } else {
      const runtime::Parameters controllers = parameters.child("controllers", "controllers");
      for (const auto& name : controllers.keys()) {
        const runtime::Parameters own = controllers.child(name, "controller '" + name + "'");
        add(name, own.get<std::string>("type", name), own);
        own.reject_unknown();
      }
      active = parameters.get<std::string>("active", active);
    }
    if (!host_->list().empty() && !has(kHoldController)) {
      add(kHoldController, kHoldController, runtime::Parameters());
    }
    try {
      host_->set_initial(active);
    } catch (const Error& e) {
      throw runtime::ParameterError(parameters.where("active") + ": " + e.what());
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
    service_.emplace(*context.participant, options.robot, context.instance, *host_);
    service_->publish_parameters();
  }

  void on_activate() override { start_ns_ = -1; }

  bool event_driven() const override { return wait_for_state_; }
  bool wait_for_event(std::int64_t /*timeout_ns*/) override {
    try {
      robot_->read_estimates(EstimateKind::joint_position, newest_q_, ReadMode::blocking);
      return true;
    } catch (const TimeoutError&) {
      ++event_timeouts_;  // no new estimate within state_timeout_s
    } catch (const StaleDataError&) {
      ++event_timeouts_;
    }
    return false;
  }

  void update(std::int64_t time_ns, std::int64_t period_ns) override {
    if (start_ns_ < 0) {
      start_ns_ = time_ns;
      next_progress_ns_ = time_ns;
    }
    const double t = 1e-9 * static_cast<double>(time_ns - start_ns_);
    host_->tick(t, 1e-9 * static_cast<double>(period_ns));
    Controller* active = host_->active_controller();
    if (active) {
      publish_signals(*active);
      if (active->finished() && !exit_requested_) {
        // The run is over: end the hosting process (wbi_host shuts the
        // components down, so the summary is printed), and `wbi launch` with it.
        exit_requested_ = true;
        runtime::request_process_exit(0);
      }
    }
    if (active && progress_period_s_ > 0 && time_ns >= next_progress_ns_) {
      next_progress_ns_ += static_cast<std::int64_t>(progress_period_s_ * 1e9);
      active->progress(progress_line_.data(), progress_line_.size());
      std::printf("t = %6.2f s  %s\n", t, progress_line_.data());
      std::fflush(stdout);
    }
  }

  void on_shutdown() override {
    if (host_) {
      std::printf("stale cycles: %llu\n",
                  static_cast<unsigned long long>(stale_cycles() + event_timeouts_));
      if (const std::string summary = host_->summary(); !summary.empty()) {
        std::printf("%s\n", summary.c_str());
      }
      std::fflush(stdout);
    }
    service_.reset();
    signals_publisher_.reset();
    host_.reset();
    if (robot_) {
      robot_->close();
    }
  }

 private:
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
      controller = controller_types().create(type);
    } catch (const std::invalid_argument& e) {
      throw runtime::ParameterError(parameters.where("type") + ": " + e.what());
    }
    ParameterTable& table = host_->add(name, type, std::move(controller));
    read_declared(parameters, table);
    try {
      host_->configure(name);
    } catch (const Error& e) {
      throw runtime::ParameterError(parameters.where() + ": " + e.what());
    }
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

  std::string single_;
  std::unique_ptr<WholeBodyInterface> robot_;
  std::optional<ControllerHost> host_;
  std::optional<HostService> service_;  // after host_: destroyed first
  double progress_period_s_ = 1.0;
  bool wait_for_state_ = false;
  Eigen::VectorXd newest_q_;  // wait_for_event's read (the tick reads the same sample again)
  std::int64_t start_ns_ = -1;
  std::int64_t next_progress_ns_ = 0;
  std::uint64_t event_timeouts_ = 0;
  std::array<char, 160> progress_line_{};
  bool exit_requested_ = false;
  runtime::StatusCounter* new_estimators_ = nullptr;
  std::unique_ptr<dds::Publisher<msg::Signals>> signals_publisher_;
  msg::Signals signals_;
  const Controller* signals_of_ = nullptr;  // whose names signals_ carries
  std::uint64_t signals_seq_ = 0;
};

}  // namespace

void register_components(runtime::Registry& registry) {
  registry.add(
      "controller_host", [] { return std::make_unique<ControllerHostComponent>(""); },
      "runs controllers on a robot's joints: lifecycle, switching, live parameters, hold");
  for (const auto& type : controller_types().names()) {
    if (type == kHoldController) {
      continue;
    }
    registry.add(
        type, [type] { return std::make_unique<ControllerHostComponent>(type); },
        controller_types().description(type) + " (a controller host with this one controller)");
  }
}

}  // namespace wbi::controllers
