#include "robot_connection.hpp"

#include <algorithm>
#include <optional>

#include <wbi/msg/joint_torque_sensors.hpp>

namespace wbi::proxy {

std::int64_t system_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

RobotConnection::RobotConnection(const DdsInterfaceOptions& options_)
    : options(options_),
      participant(options.shared_participant != nullptr
                      ? *options.shared_participant
                      : own_participant.emplace(options.participant)),
      description(participant, dds::topics::description(options.robot), dds::qos::kLatched, nullptr,
                  dds::ProducerPolicy::one(options.on_producer_event)),
      state(participant, dds::topics::state(options.robot), dds::qos::kStream,
            "state estimates of robot '" + options.robot + "' on " +
                dds::topics::state(options.robot),
            dds::ProducerPolicy::one(options.on_producer_event)) {
  if (options.read_sensors) {
    subscribe_sensors();
  }
}

void RobotConnection::subscribe_sensors() {
  sensors = std::make_unique<Stream<wbi::msg::SensorSample, kSensorReads>>(
      participant, dds::topics::sensors(options.robot), dds::qos::kStream,
      "sensor samples of robot '" + options.robot + "' on " + dds::topics::sensors(options.robot),
      dds::ProducerPolicy::owned_by(dds::description_owner(participant, description),
                                    options.on_producer_event));
}

Stream<wbi::msg::SensorSample, kSensorReads>& RobotConnection::sensor_stream() {
  if (!sensors) {
    subscribe_sensors();
    // The first sample is there as soon as the reader matched the robot's
    // writer; a read that finds none fails as any read of a silent stream does.
    sensors->read_first(options.blocking_read_timeout, [](const wbi::msg::SensorSample&) {});
    sensors->rewind_reads();
  }
  return *sensors;
}

void RobotConnection::wait(std::chrono::steady_clock::time_point deadline,
                           std::vector<std::string>& missing) {
  using Clock = std::chrono::steady_clock;
  const auto remaining = [&] { return std::max(Clock::duration::zero(), deadline - Clock::now()); };
  if (!description.wait_newer(description_rx, 0, remaining())) {
    missing.push_back("the robot description on " + dds::topics::description(options.robot) +
                      " (sensor component)");
  }
  if (sensors && !sensors->read_first(remaining(), [](const wbi::msg::SensorSample&) {})) {
    missing.push_back("sensor samples on " + dds::topics::sensors(options.robot) +
                      " (sensor component)");
  }
  if (!state.read_first(remaining(), [&](const wbi::msg::StateEstimate& estimate) {
        first_positions = estimate.q();
        external_wrench_links.clear();
        for (const auto& wrench : estimate.external_wrenches()) {
          external_wrench_links.push_back(wrench.link().to_string());
        }
      })) {
    missing.push_back("state estimates on " + dds::topics::state(options.robot) + " (estimator)");
  }
  // The first blocking read of each kind returns the newest sample, the one
  // init() saw included; later ones wait for a newer one. In lockstep the robot
  // holds tick 0 until a command computed from tick 0's sample answers it (a
  // mode switch does not: docs/conventions.md), so that read must not wait
  // for tick 1.
  if (sensors) {
    sensors->mark_init_sample(lockstep());
  }
  state.mark_init_sample(lockstep());
}

void RobotConnection::resolve(const IdList& joints) {
  controlled = joints;
  const auto& names = description_rx.sample.joint_names();
  robot_index.clear();
  for (const auto& joint : controlled) {
    std::optional<std::size_t> found;
    for (std::size_t r = 0; r < names.size(); ++r) {
      if (names[r] == joint) {
        found = r;
      }
    }
    if (!found) {
      std::string known;
      for (const auto& name : names) {
        known += (known.empty() ? "" : ", ") + name.to_string();
      }
      throw Error("joint '" + joint + "' is not a joint of robot '" + options.robot +
                  "' (its joints: " + known + ")");
    }
    robot_index.push_back(static_cast<std::uint16_t>(*found));
  }
  imu_names.clear();
  force_torque_names.clear();
  for (const auto& sensor : description_rx.sample.sensors()) {
    if (sensor.kind() == wbi::msg::SensorKind::IMU) {
      imu_names.push_back(sensor.name().to_string());
    } else if (sensor.kind() == wbi::msg::SensorKind::FORCE_TORQUE) {
      force_torque_names.push_back(sensor.name().to_string());
    }
  }
  torque_sensor = wbi::msg::joint_torque_sensors(description_rx.sample);
}

std::map<std::string, double> RobotConnection::locked_positions() const {
  std::map<std::string, double> locked = options.locked_positions;
  const auto& names = description_rx.sample.joint_names();
  const auto& measured = first_positions;
  for (std::size_t r = 0; r < names.size() && r < measured.size(); ++r) {
    const std::string name = names[r].to_string();
    const bool is_controlled =
        std::find(controlled.begin(), controlled.end(), name) != controlled.end();
    if (!is_controlled && locked.count(name) == 0) {
      locked[name] = measured[r];
    }
  }
  return locked;
}

void RobotConnection::gather(const std::vector<double>& robot_values, int first, int count,
                             VectorRef out, const char* what) const {
  for (int k = 0; k < count; ++k) {
    const auto r = robot_index[static_cast<std::size_t>(first + k)];
    if (r >= robot_values.size()) {
      throw Error(std::string("robot '") + options.robot + "' sends no " + what);
    }
    out[k] = robot_values[r];
  }
}

void RobotConnection::require_torque_sensors(const std::vector<double>& torques, int first,
                                             int count) const {
  auto sensed = [&](int k) {
    const auto r = robot_index[static_cast<std::size_t>(first + k)];
    return !torques.empty() && r < torque_sensor.size() && torque_sensor[r];
  };
  int missing = 0;
  for (int k = 0; k < count; ++k) {
    missing += sensed(k) ? 0 : 1;
  }
  if (missing == 0) {
    return;
  }
  std::string joints;
  for (int k = 0; k < count; ++k) {
    if (!sensed(k)) {
      joints += (joints.empty() ? "" : ", ") + controlled[static_cast<std::size_t>(first + k)];
    }
  }
  std::string with;
  const auto& names = description_rx.sample.joint_names();
  for (std::size_t r = 0; !torques.empty() && r < names.size() && r < torque_sensor.size(); ++r) {
    if (torque_sensor[r]) {
      with += (with.empty() ? "" : ", ") + names[r].to_string();
    }
  }
  throw Error("robot '" + options.robot + "' has no joint-torque sensor on joint" +
              (missing > 1 ? "s " : " ") + joints +
              (with.empty() ? " (it has no joint-torque sensors)"
                            : " (the joints with one: " + with + ")"));
}

void RobotConnection::require_init() const {
  if (!initialized) {
    throw Error("the whole-body interface of robot '" + options.robot +
                "' is not initialized: call init() first");
  }
}

}  // namespace wbi::proxy
