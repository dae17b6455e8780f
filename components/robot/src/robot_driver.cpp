#include "wbi/robot/robot_driver.hpp"

#include <algorithm>
#include <stdexcept>

#include "actuator_side.hpp"
#include "sensor_side.hpp"

namespace wbi::robot {

namespace {

class RobotDriver final : public runtime::Component {
 public:
  explicit RobotDriver(BackendFactory factory) : factory_(std::move(factory)) {}

  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    const auto robot = parameters.require<std::string>("robot");
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
    actuation::JointControllerConfig control;
    control.watchdog_timeout = parameters.get<double>("watchdog_timeout_s", 0.1);
    control.reference_speed = parameters.get<double>("reference_speed", 0.5);
    hold_at_start_ = parameters.get<bool>("hold_at_start", true);
    const auto urdf = parameters.get<std::string>("urdf", "");  // for the description, if known
    const bool floating_base = parameters.get<bool>("floating_base", false);

    backend_ = factory_(parameters);
    if (!backend_) {
      throw std::runtime_error("the backend factory of '" + context.type + "' made no backend");
    }
    backend_->configure();
    const auto& description = backend_->description();
    auto& participant = *context.participant;
    if (has("sensors")) {
      sensors_ = std::make_unique<SensorSide>(participant, robot, description, urdf, floating_base);
    }
    if (has("actuators")) {
      actuators_ =
          std::make_unique<ActuatorSide>(participant, robot, description, control, report());
    }
  }

  void on_activate() override {
    seq_ = 0;
    if (!actuators_) {
      return;  // sensors only: read, never power
    }
    backend_->activate();
    if (hold_at_start_) {
      backend_->read(actuation::Time(0), actuation::Duration(0));
      actuators_->hold(backend_->readings(), backend_->readings().joint_stamp);
    }
  }

  void on_deactivate() override {
    if (backend_->state() == actuation::LifecycleState::kActive) {
      backend_->deactivate();
    }
  }

  void on_cleanup() override {
    actuators_.reset();  // first: no command callback after this
    sensors_.reset();
    if (backend_) {
      backend_->shutdown();
      backend_.reset();
    }
  }

  void on_shutdown() override { on_cleanup(); }

  void read(std::int64_t time_ns, std::int64_t period_ns) override {
    backend_->read(actuation::Time(time_ns), actuation::Duration(period_ns));
    if (sensors_) {
      const auto& readings = backend_->readings();
      // the source stamp of the joint quantities; the cycle's time if the backend has none
      const auto stamp = readings.joint_stamp.count() != 0 ? readings.joint_stamp.count() : time_ns;
      sensors_->publish(readings, seq_++, stamp);
    }
  }

  void update(std::int64_t time_ns, std::int64_t period_ns) override {
    if (actuators_) {
      actuators_->begin_tick(actuation::Time(time_ns));
      actuators_->update(actuation::Time(time_ns), actuation::Duration(period_ns),
                         backend_->readings(), backend_->commands());
    }
  }

  void write(std::int64_t time_ns, std::int64_t period_ns) override {
    if (actuators_) {
      backend_->write(actuation::Time(time_ns), actuation::Duration(period_ns));
    }
  }

 private:
  BackendFactory factory_;
  bool hold_at_start_ = true;
  std::uint64_t seq_ = 0;
  std::unique_ptr<actuation::RobotBackend> backend_;
  std::unique_ptr<SensorSide> sensors_;
  std::unique_ptr<ActuatorSide> actuators_;
};

}  // namespace

void register_driver(runtime::Registry& registry, const std::string& type, BackendFactory factory,
                     std::string description) {
  registry.add(
      type, [factory] { return std::make_unique<RobotDriver>(factory); }, std::move(description));
}

}  // namespace wbi::robot
