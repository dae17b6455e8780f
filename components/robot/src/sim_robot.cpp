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

#include <wbi/actuation/joint_controller.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/sim/sim_backend.hpp>

#include "command_translation.hpp"
#include "messages.hpp"

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

    sim_ = std::make_unique<sim::SimBackend>(sim::load_sim_config_file(config_path.string()));
    sim_->configure();
    const auto& description =
        sim_->description();  // its robot name is the URDF's; topics use robot_
    controller_ = std::make_unique<actuation::JointController>(description, control);
    reference_speed_.assign(description.joint_names.size(), control.reference_speed);
    answered_.clear();
    for (const auto& name : controllers) {
      answered_[name] = -1;
    }

    auto& participant = *context.participant;
    description_ = std::make_unique<dds::Publisher<wbi::msg::RobotDescription>>(
        participant, dds::topics::description(robot_), dds::qos::kLatched);
    sensors_ = std::make_unique<dds::Publisher<wbi::msg::SensorSample>>(
        participant, dds::topics::sensors(robot_), dds::qos::kStream);
    ground_truth_ = std::make_unique<dds::Publisher<wbi::msg::GroundTruth>>(
        participant, dds::topics::ground_truth(robot_), dds::qos::kStream);
    clock_ = std::make_unique<dds::Publisher<wbi::msg::SimulationClock>>(
        participant, dds::topics::kClock, dds::qos::kStream);
    commands_ = std::make_unique<dds::Subscriber<wbi::msg::ActuatorCommand>>(
        participant, dds::topics::commands(robot_), dds::qos::kCommand,
        [this](const wbi::msg::ActuatorCommand& c, const dds::detail::SampleInfo&) {
          on_command(c);
        });
    parameters_ = std::make_unique<dds::Subscriber<wbi::msg::ControlParameters>>(
        participant, dds::topics::control_parameters(robot_), dds::qos::kCommand,
        [this](const wbi::msg::ControlParameters& p, const dds::detail::SampleInfo&) {
          on_parameters(p);
        });

    describe(description, robot_, config_path.string(), sim_->model().floating_base,
             description_message_);
    description_->publish(description_message_);
    prepare_sensor_sample(description, robot_, sensor_message_);
  }

  void on_activate() override {
    sim_->activate();
    if (hold_at_start_) {
      // Like a real robot's boards: joints hold where they are until a controller
      // commands them (without a watchdog: POSITION is not a streaming mode).
      actuation::JointCommandBatch hold;
      hold.modes.assign(sim_->description().joint_names.size(), actuation::ControlMode::kPosition);
      sim_->read(sim_->stamp(), std::chrono::nanoseconds(0));
      const auto& q = sim_->readings().position;
      hold.values.assign(q.data(), q.data() + q.size());
      std::lock_guard lock(mutex_);
      const auto result = controller_->submit(hold, sim_->stamp());
      if (!result.ok) {
        throw std::runtime_error("cannot hold the initial posture: " + result.error);
      }
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
    commands_.reset();  // first: no callback after this
    parameters_.reset();
    clock_.reset();
    ground_truth_.reset();
    sensors_.reset();
    description_.reset();
    controller_.reset();
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

  // Runs on a DDS thread: stages the command for the next tick; never throws into DDS.
  void on_command(const wbi::msg::ActuatorCommand& command) {
    std::lock_guard lock(mutex_);
    const std::string error = to_batch(command, reference_speed_, batch_);
    const auto result = error.empty()
                            ? controller_->submit(batch_, actuation::Time(tick_stamp_ns_.load()))
                            : actuation::CommandResult{false, error};
    if (!result.ok) {
      ++rejected_;
      std::cerr << "sim_robot '" << robot_ << "': command rejected: " << result.error << std::endl;
    }
    const auto sender = answered_.find(command.controller().to_string());
    if (sender != answered_.end()) {
      sender->second = std::max(sender->second, static_cast<std::int64_t>(command.tick()));
      answered_changed_.notify_all();
    }
  }

  void on_parameters(const wbi::msg::ControlParameters& message) {
    std::lock_guard lock(mutex_);
    const auto& names = sim_->description().joint_names;
    for (std::size_t k = 0; k < message.joints().size(); ++k) {
      const auto joint = message.joints()[k];
      if (joint >= names.size()) {
        std::cerr << "sim_robot '" << robot_ << "': control parameters for joint index " << joint
                  << " out of range: ignored" << std::endl;
        return;
      }
      const auto value = [&](const std::vector<double>& values, double current) {
        return k < values.size() && !std::isnan(values[k]) ? values[k] : current;
      };
      auto gains = controller_->gains(joint);
      gains.kp = value(message.kp(), gains.kp);
      gains.ki = value(message.ki(), gains.ki);
      gains.kd = value(message.kd(), gains.kd);
      controller_->set_gains(names[joint], gains);
      reference_speed_[joint] = value(message.reference_speed(), reference_speed_[joint]);
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
      ++lockstep_timeouts_;
      std::cerr << "sim_robot '" << robot_ << "': tick " << tick
                << " not answered by every controller within " << timeout_s << " s: stepping on"
                << std::endl;
    }
  }

  void run() {
    const auto period =
        std::chrono::nanoseconds(static_cast<std::int64_t>(sim_->config().step * 1e9));
    const auto start = Clock::now();
    for (std::uint64_t tick = 0; running_; ++tick) {
      if (duration_s_ > 0.0 && sim_->time() >= duration_s_) {
        break;
      }
      const auto now = sim_->stamp();
      tick_stamp_ns_ = now.count();  // the command callbacks' notion of "now" (watchdog)
      sim_->read(now, period);
      publish_tick(tick);
      if (lockstep_) {
        wait_for_answers(tick);
      } else {
        std::this_thread::sleep_until(start + period * (tick + 1));  // real-time pacing
      }
      {
        std::lock_guard lock(mutex_);
        controller_->update(now, period, sim_->readings(), sim_->commands());
      }
      sim_->write(now, period);
      sim_->step();
    }
  }

  void publish_tick(std::uint64_t tick) {
    fill_sensor_sample(sim_->readings(), tick, sim_->stamp().count(), sensor_message_);
    sensors_->publish(sensor_message_);
    fill_ground_truth(sim_->ground_truth(), robot_, tick, sim_->stamp().count(), truth_message_);
    ground_truth_->publish(truth_message_);
    clock_message_.time_ns(sim_->stamp().count());
    clock_message_.tick(tick);
    clock_message_.step_ns(static_cast<std::int64_t>(sim_->config().step * 1e9));
    clock_message_.lockstep(lockstep_);
    clock_->publish(clock_message_);
  }

  std::string robot_;
  bool lockstep_ = false;
  double lockstep_timeout_s_ = 2.0;
  double lockstep_start_timeout_s_ = 60.0;
  std::atomic<std::int64_t> tick_stamp_ns_{0};
  double duration_s_ = 0.0;
  bool hold_at_start_ = true;

  std::unique_ptr<sim::SimBackend> sim_;
  std::unique_ptr<actuation::JointController> controller_;
  std::vector<double> reference_speed_;  // [n] POSITION-mode speed per joint
  actuation::JointCommandBatch batch_;   // reused for every command

  std::mutex mutex_;  // guards controller_, batch_, answered_ between DDS threads and the loop
  std::condition_variable answered_changed_;
  std::map<std::string, std::int64_t> answered_;  // lockstep: newest tick answered per controller
  std::uint64_t rejected_ = 0;
  std::uint64_t lockstep_timeouts_ = 0;
  std::atomic<bool> running_{false};
  std::thread loop_;

  wbi::msg::RobotDescription description_message_;
  wbi::msg::SensorSample sensor_message_;
  wbi::msg::GroundTruth truth_message_;
  wbi::msg::SimulationClock clock_message_;
  std::unique_ptr<dds::Publisher<wbi::msg::RobotDescription>> description_;
  std::unique_ptr<dds::Publisher<wbi::msg::SensorSample>> sensors_;
  std::unique_ptr<dds::Publisher<wbi::msg::GroundTruth>> ground_truth_;
  std::unique_ptr<dds::Publisher<wbi::msg::SimulationClock>> clock_;
  std::unique_ptr<dds::Subscriber<wbi::msg::ActuatorCommand>> commands_;
  std::unique_ptr<dds::Subscriber<wbi::msg::ControlParameters>> parameters_;
};

}  // namespace

void register_components(runtime::Registry& registry) {
  registry.add<SimRobot>(
      "sim_robot", "simulated robot: sensor samples, ground truth and clock out, commands in");
}

}  // namespace wbi::robot
