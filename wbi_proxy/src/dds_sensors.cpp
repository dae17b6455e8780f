#include "dds_sensors.hpp"

#include <wbi/msg/eigen.hpp>

#include "size_check.hpp"

namespace wbi::proxy {

const IdList& DdsSensors::sensor_list(SensorKind kind) const {
  switch (kind) {
    case SensorKind::imu:
    case SensorKind::accelerometer:
    case SensorKind::gyroscope:
      return robot_.imu_names;
    case SensorKind::force_torque:
      return robot_.force_torque_names;
    default:
      return robot_.controlled;
  }
}

Stamp DdsSensors::read_sensors(SensorKind kind, VectorRef values, ReadMode mode) {
  robot_.require_init();
  const int count = static_cast<int>(sensor_list(kind).size());
  check_size("sensor values", values.size(), count * sensor_width(kind));
  return read_range(kind, 0, count, values, mode);
}

Stamp DdsSensors::read_sensor(SensorKind kind, int index, VectorRef values, ReadMode mode) {
  robot_.require_init();
  check_index("sensor", index, static_cast<int>(sensor_list(kind).size()));
  check_size("sensor values", values.size(), sensor_width(kind));
  return read_range(kind, index, 1, values, mode);
}

Stamp DdsSensors::read_range(SensorKind kind, int first, int count, VectorRef out, ReadMode mode) {
  const auto index = static_cast<std::size_t>(kind);
  const auto& options = robot_.options;
  if (kind == SensorKind::encoder_velocity || kind == SensorKind::encoder_acceleration) {
    // No speed sensors on the wire: the estimator's values stand in for them.
    const bool velocity = kind == SensorKind::encoder_velocity;
    robot_.state.read(index, mode, options.max_age_s, options.blocking_read_timeout,
                      [&](const wbi::msg::StateEstimate& state) {
                        robot_.gather(velocity ? state.dq() : state.ddq(), first, count, out,
                                      velocity ? "joint velocities" : "joint accelerations");
                      });
    return robot_.state.stamp();
  }
  auto& sensors = robot_.sensor_stream();
  sensors.read(
      index, mode, options.max_age_s, options.blocking_read_timeout,
      [&](const wbi::msg::SensorSample& sample) { read_sample(sample, kind, first, count, out); });
  return sensors.stamp();
}

void DdsSensors::read_sample(const wbi::msg::SensorSample& sample, SensorKind kind, int first,
                             int count, VectorRef out) const {
  switch (kind) {
    case SensorKind::encoder_position:
      robot_.gather(sample.encoder_position(), first, count, out, "encoder positions");
      break;
    case SensorKind::joint_torque:
      robot_.require_torque_sensors(sample.joint_torque(), first, count);
      robot_.gather(sample.joint_torque(), first, count, out, "joint torques");
      break;
    case SensorKind::motor_pwm:
      robot_.gather(sample.motor_pwm(), first, count, out, "motor PWM");
      break;
    case SensorKind::force_torque:
      for (int i = 0; i < count; ++i) {
        msg::to_eigen(sample.force_torque().at(static_cast<std::size_t>(first + i)).wrench(),
                      out.segment<6>(6 * i));
      }
      break;
    default:  // imu, accelerometer, gyroscope
      for (int i = 0; i < count; ++i) {
        const auto& imu = sample.imus().at(static_cast<std::size_t>(first + i));
        const Eigen::Vector3d w = msg::to_eigen(imu.angular_velocity());
        const Eigen::Vector3d a = msg::to_eigen(imu.linear_acceleration());
        if (kind == SensorKind::imu) {
          out.segment<10>(10 * i) << msg::to_wxyz(imu.orientation()), w, a;
        } else if (kind == SensorKind::gyroscope) {
          out.segment<3>(3 * i) = w;
        } else {
          out.segment<3>(3 * i) = a;
        }
      }
  }
}

}  // namespace wbi::proxy
