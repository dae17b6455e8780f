#include "wbi/robot/robot_driver.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "actuator_side.hpp"
#include "ground_truth_summary.hpp"
#include "robot_name.hpp"
#include "sensor_side.hpp"
#include "simulation_side.hpp"
#include "tick_pacer.hpp"
#include "wbi/runtime/console_line.hpp"
#include "wbi/runtime/process_exit.hpp"

namespace wbi::robot {

namespace {

using actuation::Duration;
using actuation::Time;

struct Sides {
  bool sensors = true;
  bool actuators = true;
};

Sides read_sides(const runtime::Parameters& parameters) {
  const auto sides = parameters.get<std::vector<std::string>>("sides", {"sensors", "actuators"});
  if (sides.empty()) {
    throw runtime::ParameterError(parameters.where("sides") +
                                  ": needs at least one of sensors, actuators");
  }
  for (const auto& side : sides) {
    if (side != "sensors" && side != "actuators") {
      throw runtime::ParameterError(parameters.where("sides") + ": unknown side '" + side +
                                    "' (sensors, actuators)");
    }
  }
  const auto has = [&](const char* side) {
    return std::find(sides.begin(), sides.end(), side) != sides.end();
  };
  return {has("sensors"), has("actuators")};
}

// A simulation's pacing and run length (robot_driver.hpp, "Simulations only").
struct SimulationOptions {
  bool lockstep = false;
  LockstepOptions lockstep_options;
  bool real_time = true;              // paced at real time (default: unless lockstep)
  double real_time_max_lag_s = 0.02;  // a longer delay is not caught up (tick_pacer.hpp)
  double duration_s = 0.0;            // 0: no end
  std::string ground_truth_file;      // empty: none (simulation_side.hpp)
};

SimulationOptions read_simulation_options(const runtime::Parameters& parameters) {
  SimulationOptions options;
  options.lockstep = parameters.get<bool>("lockstep", false);
  auto& lockstep = options.lockstep_options;
  lockstep.controllers = parameters.get<std::vector<std::string>>("lockstep_controllers", {});
  if (options.lockstep && lockstep.controllers.empty()) {
    throw runtime::ParameterError(parameters.where("lockstep_controllers") +
                                  ": lockstep needs the names of the controllers to wait for");
  }
  lockstep.timeout_s = parameters.get<double>("lockstep_timeout_s", 2.0);
  lockstep.start_timeout_s = parameters.get<double>("lockstep_start_timeout_s", 60.0);
  options.real_time = parameters.get<bool>("real_time", !options.lockstep);
  options.real_time_max_lag_s = parameters.get<double>("real_time_max_lag_s", 0.02);
  if (!(options.real_time_max_lag_s >= 0.0)) {
    throw runtime::ParameterError(parameters.where("real_time_max_lag_s") +
                                  ": must be >= 0 (seconds of delay caught up)");
  }
  options.duration_s = parameters.get<double>("duration_s", 0.0);
  options.ground_truth_file = parameters.get<std::string>("ground_truth_file", "");
  return options;
}

// The one robot loop (wbi/robot/robot_driver.hpp). A tick is sense → control →
// actuate; a real robot's ticks are the runner's cycles (read, update, write),
// a simulation's are run by step_until_stopped() on the driver's own thread,
// with its tick pacers between sense and control and step() after actuate.
class RobotDriver final : public runtime::Component {
 public:
  explicit RobotDriver(BackendFactory factory) : backend_factory_(std::move(factory)) {}
  explicit RobotDriver(SimulationFactory factory) : simulation_factory_(std::move(factory)) {}

  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    robot_ = parameters.require<std::string>("robot");
    who_ = context.type + " '" + robot_ + "'";
    clock_ = context.clock;
    const bool simulated = static_cast<bool>(simulation_factory_);
    const Sides sides = simulated ? Sides{} : read_sides(parameters);
    actuation::JointControllerConfig control;
    control.watchdog_timeout = parameters.get<double>("watchdog_timeout_s", 0.1);
    control.reference_speed = parameters.get<double>("reference_speed", 0.5);
    hold_at_start_ = parameters.get<bool>("hold_at_start", true);
    const bool require_claims = parameters.get<bool>("require_claims", false);
    // The description names the URDF the backend loaded (a model service or a
    // proxy may load it for frames); a real robot's driver may be told.
    std::string urdf;
    std::optional<bool> floating_base;
    SimulationOptions simulation;
    if (simulated) {
      simulation = read_simulation_options(parameters);
      duration_s_ = simulation.duration_s;
    } else {
      urdf = parameters.get<std::string>("urdf", "");
      if (parameters.has("floating_base")) {
        floating_base = parameters.get<bool>("floating_base", false);
      }
    }

    const double name_check_s = parameters.get<double>("name_check_s", 0.5);
    auto& participant = *context.participant;
    std::optional<RobotNameClaim> name;
    if (sides.sensors) {  // the side that publishes the robot takes its name
      name.emplace(participant, robot_, name_check_s);
    }
    make_backend(parameters, context);
    backend_->configure();
    const auto& description = backend_->description();
    if (sides.sensors) {
      sensors_ = std::make_unique<SensorSide>(
          participant, robot_, description, urdf.empty() ? description.urdf : urdf,
          floating_base.value_or(description.floating_base), simulated && simulation.lockstep);
    }  // its description writer holds the name from here on
    ActuatorSide::CommandObserver observer;
    if (simulation_) {
      make_simulation_parts(participant, simulation);
      observer = [this](const wbi::msg::ActuatorCommand& command, std::int64_t written_ns) {
        for (const auto& pacer : pacers_) {
          pacer->observe(command, written_ns);  // lockstep bookkeeping
        }
      };
    }
    if (sides.actuators) {
      actuators_ =
          std::make_unique<ActuatorSide>(participant, robot_, description, control, report(),
                                         events(), std::move(observer), require_claims);
    }
  }

  void on_activate() override {
    seq_ = 0;
    if (actuators_) {
      backend_->activate();
      if (hold_at_start_) {
        const Time now = simulation_ ? simulation_->stamp() : Time(clock_->now_ns());
        backend_->read(now, Duration(0));
        actuators_->hold(backend_->readings(), source_stamp(now));
      }
    }  // else sensors only: read, never power
    if (simulation_) {
      for (const auto& pacer : pacers_) {
        pacer->start();
      }
      running_ = true;
      loop_ = std::thread([this] { run_simulation(); });
    }
  }

  void on_deactivate() override {
    stop_simulation();
    if (backend_->state() == wbi::LifecycleState::active) {
      backend_->deactivate();
    }
  }

  void on_cleanup() override {
    stop_simulation();
    actuators_.reset();  // first: no command callback after this
    pacers_.clear();
    simulation_side_.reset();
    sensors_.reset();
    simulation_ = nullptr;
    if (backend_) {
      backend_->shutdown();
      backend_.reset();
    }
  }

  void on_shutdown() override { on_cleanup(); }

  // The runner's cycle: a real robot's tick (a simulation runs its own).
  void read(std::int64_t time_ns, std::int64_t period_ns) override {
    if (!simulation_) {
      sense(Time(time_ns), Duration(period_ns));
    }
  }
  void update(std::int64_t time_ns, std::int64_t period_ns) override {
    if (!simulation_) {
      control(Time(time_ns), Duration(period_ns));
    }
  }
  void write(std::int64_t time_ns, std::int64_t period_ns) override {
    if (!simulation_) {
      actuate(Time(time_ns), Duration(period_ns));
    }
  }

 private:
  void make_backend(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) {
    if (simulation_factory_) {
      auto simulation = simulation_factory_(parameters);
      simulation_ = simulation.get();
      backend_ = std::move(simulation);
    } else {
      backend_ = backend_factory_(parameters);
    }
    if (!backend_) {
      throw std::runtime_error("the backend factory of '" + context.type + "' made no backend");
    }
  }

  // A simulation's own topics, and its tick pacers, waited in this order.
  void make_simulation_parts(dds::Participant& participant, const SimulationOptions& options) {
    try {
      simulation_side_ =
          std::make_unique<SimulationSide>(participant, robot_, simulation_->step_period(),
                                           options.lockstep, options.ground_truth_file);
    } catch (const std::runtime_error& e) {
      throw runtime::ParameterError(std::string("ground_truth_file: ") + e.what());
    }
    auto& timeouts = report().counter("lockstep_timeouts");  // 0 unless lockstep
    if (options.lockstep) {
      pacers_.push_back(std::make_unique<LockstepPacer>(
          options.lockstep_options, simulation_->step_period(), who_, timeouts, events()));
    }
    auto& stalls = report().counter("real_time_stalls");  // 0 unless real time
    if (options.real_time) {
      pacers_.push_back(std::make_unique<RealTimePacer>(
          simulation_->step_period(),
          std::chrono::duration_cast<std::chrono::nanoseconds>(
              std::chrono::duration<double>(options.real_time_max_lag_s)),
          who_, stalls, events()));
    }
  }

  // The source stamp of the joint quantities; the tick's time if the backend has none.
  Time source_stamp(Time now) const {
    const Time stamp = backend_->readings().joint_stamp;
    return stamp.count() != 0 ? stamp : now;
  }

  // Tick seq_ begins: read the backend, publish what it read.
  void sense(Time now, Duration period) {
    if (actuators_) {
      actuators_->begin_tick(now);  // the command callbacks' notion of "now" (watchdog)
    }
    backend_->read(now, period);
    if (sensors_) {
      sensors_->publish(backend_->readings(), seq_, source_stamp(now).count());
    }
    if (simulation_side_) {
      simulation_side_->publish(simulation_->ground_truth(), seq_, simulation_->stamp());
    }
  }

  // The commands staged since the last tick, through the joint controller.
  void control(Time now, Duration period) {
    if (actuators_) {
      actuators_->update(now, period, backend_->readings(), backend_->commands());
    }
  }

  void actuate(Time now, Duration period) {
    if (actuators_) {
      backend_->write(now, period);
    }
    ++seq_;
  }

  // The simulation's thread: a diverged simulation (its state no longer
  // finite) throws; that stops the stepping with an error on the status topic,
  // and the hosting process ends with exit code 1 (under wbi_host: the robot's
  // components shut down in order and `wbi launch` sees a required process
  // fail) instead of leaving controllers to run on a robot that is gone.
  void run_simulation() {
    try {
      GroundTruthSummary summary(backend_->description(), simulation_->ground_truth());
      step_until_stopped(summary);
      simulation_side_->close_file();  // complete once stepping ended, whatever stops the process
      std::ostringstream report;
      summary.print(report, who_);
      for (const auto& pacer : pacers_) {
        if (const std::string line = pacer->summary(); !line.empty()) {
          report << who_ << ": " << line << "\n";
        }
      }
      if (std::string text = std::move(report).str(); !text.empty()) {
        text.pop_back();  // print_line adds the last newline
        runtime::print_line(stdout, text);
      }
    } catch (const std::exception& e) {
      const std::string what =
          "simulation stopped at t = " + std::to_string(simulation_->time()) + " s: " + e.what();
      report().set_error(what);
      runtime::print_line(stderr, who_ + ": " + what);
      try {
        simulation_side_->close_file();  // the ticks up to the failure stay readable
      } catch (const std::exception&) {
      }
      events().emit(EventSeverity::error, EventKind::divergence, what);
      runtime::request_process_exit(1);
    }
  }

  void step_until_stopped(GroundTruthSummary& summary) {
    const Duration period = simulation_->step_period();
    while (running_) {
      if (duration_s_ > 0.0 && simulation_->time() >= duration_s_) {
        // A line to wait for: a lockstep run's outcome is fixed from here on.
        std::ostringstream line;
        line << who_ << ": duration_s " << duration_s_ << " reached: stopped stepping";
        runtime::print_line(stdout, line.str());
        break;
      }
      const Time now = simulation_->stamp();
      sense(now, period);
      for (const auto& pacer : pacers_) {
        pacer->wait(seq_);  // none: free running
      }
      control(now, period);
      actuate(now, period);
      simulation_->step();
      summary.add(simulation_->ground_truth());
    }
  }

  void stop_simulation() {
    running_ = false;
    for (const auto& pacer : pacers_) {
      pacer->stop();
    }
    if (loop_.joinable()) {
      loop_.join();
    }
  }

  const BackendFactory backend_factory_;
  const SimulationFactory simulation_factory_;
  std::string robot_;
  std::string who_;  // "TYPE 'ROBOT'" in messages
  runtime::Clock* clock_ = nullptr;
  bool hold_at_start_ = true;
  double duration_s_ = 0.0;
  std::uint64_t seq_ = 0;  // the tick: sensor sample, ground truth and wbi/clock sequence

  std::unique_ptr<actuation::RobotBackend> backend_;
  actuation::SimulationBackend* simulation_ = nullptr;  // backend_, when it is a simulation
  std::unique_ptr<SensorSide> sensors_;
  std::unique_ptr<SimulationSide> simulation_side_;
  std::vector<std::unique_ptr<TickPacer>> pacers_;  // waited in order; none: free running
  std::unique_ptr<ActuatorSide> actuators_;
  std::atomic<bool> running_{false};
  std::thread loop_;
};

}  // namespace

void register_driver(runtime::Registry& registry, const std::string& type, BackendFactory factory,
                     std::string description) {
  registry.add(
      type, [factory] { return std::make_unique<RobotDriver>(factory); }, std::move(description));
}

void register_simulation(runtime::Registry& registry, const std::string& type,
                         SimulationFactory factory, std::string description) {
  registry.add(
      type, [factory] { return std::make_unique<RobotDriver>(factory); }, std::move(description));
}

}  // namespace wbi::robot
