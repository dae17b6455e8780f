#include "dds_sensors.hpp"

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
    const auto& state =
        robot_.state.take(index, mode, options.max_age_s, options.blocking_read_timeout);
    const bool velocity = kind == SensorKind::encoder_velocity;
    robot_.gather(velocity ? state.dq() : state.ddq(), first, count, out,
                  velocity ? "joint velocities" : "joint accelerations");
    return robot_.state.stamp();
  }
  auto& sensors = robot_.sensor_stream();
  const auto& sample = sensors.take(index, mode, options.max_age_s, options.blocking_read_timeout);
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
        const auto& w = sample.force_torque().at(static_cast<std::size_t>(first + i)).wrench();
        out.segment<6>(6 * i) << w.force().x(), w.force().y(), w.force().z(), w.torque().x(),
            w.torque().y(), w.torque().z();
      }
      break;
    default:  // imu, accelerometer, gyroscope
      for (int i = 0; i < count; ++i) {
        const auto& imu = sample.imus().at(static_cast<std::size_t>(first + i));
        const auto& o = imu.orientation();
        const auto& w = imu.angular_velocity();
        const auto& a = imu.linear_acceleration();
        if (kind == SensorKind::imu) {
          out.segment<10>(10 * i) << o.w(), o.x(), o.y(), o.z(), w.x(), w.y(), w.z(), a.x(), a.y(),
              a.z();
        } else if (kind == SensorKind::gyroscope) {
          out.segment<3>(3 * i) << w.x(), w.y(), w.z();
        } else {
          out.segment<3>(3 * i) << a.x(), a.y(), a.z();
        }
      }
  }
  return sensors.stamp();
}

}  // namespace wbi::proxy
