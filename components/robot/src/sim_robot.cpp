#include "wbi/robot/sim_robot.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/sim/sim_backend.hpp>

#include "actuator_side.hpp"
#include "messages.hpp"
#include "sensor_side.hpp"

namespace wbi::robot {

namespace {

using Clock = std::chrono::steady_clock;

class SimRobot final : public runtime::Component {
 public:
  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    robot_ = parameters.require<std::string>("robot");
    auto config_path = std::filesystem::path(parameters.require<std::string>("config"));
    if (config_path.is_relative() && !parameters.file().empty() &&
        parameters.file() != "<string>") {
      config_path = std::filesystem::path(parameters.file()).parent_path() / config_path;
    }
    lockstep_ = parameters.get<bool>("lockstep", false);
    const auto controllers = parameters.get<std::vector<std::string>>("lockstep_controllers", {});
    if (lockstep_ && controllers.empty()) {
      throw runtime::ParameterError(parameters.where("lockstep_controllers") +
                                    ": lockstep needs the names of the controllers to wait for");
    }
    lockstep_timeout_s_ = parameters.get<double>("lockstep_timeout_s", 2.0);
    lockstep_start_timeout_s_ = parameters.get<double>("lockstep_start_timeout_s", 60.0);
    duration_s_ = parameters.get<double>("duration_s", 0.0);
    actuation::JointControllerConfig control;
    control.watchdog_timeout = parameters.get<double>("watchdog_timeout_s", 0.1);
    control.reference_speed = parameters.get<double>("reference_speed", 0.5);
    hold_at_start_ = parameters.get<bool>("hold_at_start", true);

    sim_ = std::make_unique<sim::SimBackend>(robot_config::load_robot_config(config_path.string()));
    sim_->configure();
    const auto& description =
        sim_->description();  // its robot name is the URDF's; topics use robot_
    answered_.clear();
    for (const auto& name : controllers) {
      answered_[name] = -1;
    }
    lockstep_timeouts_ = &report().counter("lockstep_timeouts");

    auto& participant = *context.participant;
    // The description names the URDF the simulation loaded (a model service or a
    // proxy may load it for frames), not the simulation's YAML.
    sensors_ = std::make_unique<SensorSide>(participant, robot_, description, sim_->config().urdf,
                                            sim_->model().floating_base);
    ground_truth_ = std::make_unique<dds::Publisher<wbi::msg::GroundTruth>>(
        participant, dds::topics::ground_truth(robot_), dds::qos::kStream);
    clock_ = std::make_unique<dds::Publisher<wbi::msg::SimulationClock>>(
        participant, dds::topics::kClock, dds::qos::kStream);
    actuators_ = std::make_unique<ActuatorSide>(
        participant, robot_, description, control, report(),
        [this](const wbi::msg::ActuatorCommand& command) { on_answer(command); });
  }

  void on_activate() override {
    sim_->activate();
    if (hold_at_start_) {
      sim_->read(sim_->stamp(), std::chrono::nanoseconds(0));
      actuators_->hold(sim_->readings(), sim_->stamp());
    }
    running_ = true;
    loop_ = std::thread([this] { run(); });
  }

  void on_deactivate() override {
    stop_loop();
    sim_->deactivate();
  }

  void on_cleanup() override {
    stop_loop();
    actuators_.reset();  // first: no command callback after this
    clock_.reset();
    ground_truth_.reset();
    sensors_.reset();
    sim_.reset();
  }

  void on_shutdown() override { on_cleanup(); }

 private:
  void stop_loop() {
    running_ = false;
    answered_changed_.notify_all();
    if (loop_.joinable()) {
      loop_.join();
    }
  }

  // Lockstep bookkeeping, on the DDS thread after the actuator side staged the command.
  void on_answer(const wbi::msg::ActuatorCommand& command) {
    std::lock_guard lock(mutex_);
    const auto sender = answered_.find(command.controller().to_string());
    if (sender != answered_.end()) {
      sender->second = std::max(sender->second, static_cast<std::int64_t>(command.tick()));
      answered_changed_.notify_all();
    }
  }

  // Lockstep: true once every controller has answered `tick` (or on timeout, with a warning).
  void wait_for_answers(std::uint64_t tick) {
    std::unique_lock lock(mutex_);
    const auto all_answered = [&] {
      for (const auto& [name, answered] : answered_) {
        if (answered < static_cast<std::int64_t>(tick)) {
          return false;
        }
      }
      return true;
    };
    // The first tick waits for the controllers to start; later ticks for one control step.
    const double timeout_s = tick == 0 ? lockstep_start_timeout_s_ : lockstep_timeout_s_;
    if (!answered_changed_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                                    [&] { return !running_ || all_answered(); })) {
      lockstep_timeouts_->add();
      std::cerr << "sim_robot '" << robot_ << "': tick " << tick
                << " not answered by every controller within " << timeout_s << " s: stepping on"
                << std::endl;
    }
  }

  // The stepping thread: a diverged simulation (the plant's state no longer
  // finite) throws from the model library; it stops the stepping with an error
  // on the status topic instead of terminating the process.
  void run() {
    try {
      step_until_stopped();
    } catch (const std::exception& e) {
      const std::string what =
          "simulation stopped at t = " + std::to_string(sim_->time()) + " s: " + e.what();
      report().set_error(what);
      std::cerr << "sim_robot '" << robot_ << "': " << what << std::endl;
    }
  }

  void step_until_stopped() {
    const auto period =
        std::chrono::nanoseconds(static_cast<std::int64_t>(sim_->config().wbi.step * 1e9));
    const auto start = Clock::now();
    for (std::uint64_t tick = 0; running_; ++tick) {
      if (duration_s_ > 0.0 && sim_->time() >= duration_s_) {
        // A line to wait for: a lockstep run's outcome is fixed from here on.
        std::cout << "sim_robot '" << robot_ << "': duration_s " << duration_s_
                  << " reached: stopped stepping" << std::endl;
        break;
      }
      const auto now = sim_->stamp();
      actuators_->begin_tick(now);  // the command callbacks' notion of "now" (watchdog)
      sim_->read(now, period);
      publish_tick(tick);
      if (lockstep_) {
        wait_for_answers(tick);
      } else {
        std::this_thread::sleep_until(start + period * (tick + 1));  // real-time pacing
      }
      actuators_->update(now, period, sim_->readings(), sim_->commands());
      sim_->write(now, period);
      sim_->step();
    }
  }

  void publish_tick(std::uint64_t tick) {
    sensors_->publish(sim_->readings(), tick, sim_->stamp().count());
    fill_ground_truth(sim_->ground_truth(), robot_, tick, sim_->stamp().count(), truth_message_);
    ground_truth_->publish(truth_message_);
    clock_message_.time_ns(sim_->stamp().count());
    clock_message_.tick(tick);
    clock_message_.step_ns(static_cast<std::int64_t>(sim_->config().wbi.step * 1e9));
    clock_message_.lockstep(lockstep_);
    clock_->publish(clock_message_);
  }

  std::string robot_;
  bool lockstep_ = false;
  double lockstep_timeout_s_ = 2.0;
  double lockstep_start_timeout_s_ = 60.0;
  double duration_s_ = 0.0;
  bool hold_at_start_ = true;

  std::unique_ptr<sim::SimBackend> sim_;

  std::mutex mutex_;  // guards answered_ between DDS threads and the loop
  std::condition_variable answered_changed_;
  std::map<std::string, std::int64_t> answered_;  // lockstep: newest tick answered per controller
  runtime::StatusCounter* lockstep_timeouts_ = nullptr;
  std::atomic<bool> running_{false};
  std::thread loop_;

  wbi::msg::GroundTruth truth_message_;
  wbi::msg::SimulationClock clock_message_;
  std::unique_ptr<SensorSide> sensors_;
  std::unique_ptr<dds::Publisher<wbi::msg::GroundTruth>> ground_truth_;
  std::unique_ptr<dds::Publisher<wbi::msg::SimulationClock>> clock_;
  std::unique_ptr<ActuatorSide> actuators_;
};

}  // namespace

void register_components(runtime::Registry& registry) {
  registry.add<SimRobot>(
      "sim_robot", "simulated robot: sensor samples, ground truth and clock out, commands in");
}

}  // namespace wbi::robot
