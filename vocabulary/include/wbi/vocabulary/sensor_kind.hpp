// What a sensor measures: the one sensor-kind enum of the whole-body
// interface's Sensors element and of the robot description on the wire
// (idl/description.idl, SensorKind, which follows it value for value).
#pragma once

#include <cstdint>

#include "wbi/vocabulary/enum_names.hpp"

namespace wbi {

// Values per sensor, stacked in this order when all sensors of a kind are read.
// The first five are what a robot's sensors measure, numbered as the wire has
// always numbered them (recordings keep their meaning); the last four are read
// from the state estimate or from parts of an IMU. A robot description lists
// its IMU and F/T sensors.
enum class SensorKind : std::uint8_t {
  encoder_position,  // 1 per controlled joint [rad or m]
  joint_torque,      // 1 per controlled joint [N m]
  motor_pwm,         // 1 per controlled joint, duty cycle
  imu,  // 10 per IMU: orientation (w, x, y, z), gyro [rad/s], accelerometer [m/s^2], IMU axes
  force_torque,          // 6 per sensor: force [N], torque [N m], sensor frame
  encoder_velocity,      // 1 per controlled joint [rad/s] (from the state estimate when the robot
                         // has no speed sensor)
  encoder_acceleration,  // 1 per controlled joint [rad/s^2] (likewise)
  accelerometer,         // 3 per IMU [m/s^2], IMU axes, gravity included
  gyroscope,             // 3 per IMU [rad/s], IMU axes
};

template <>
struct EnumNames<SensorKind> {
  static constexpr std::array names{
      "ENCODER_POSITION", "JOINT_TORQUE",         "MOTOR_PWM",     "IMU",      "FORCE_TORQUE",
      "ENCODER_VELOCITY", "ENCODER_ACCELERATION", "ACCELEROMETER", "GYROSCOPE"};
};

constexpr const char* to_string(SensorKind kind) { return enum_name(kind); }

// Values per sensor of a kind (the counts above).
constexpr int sensor_width(SensorKind kind) {
  switch (kind) {
    case SensorKind::imu:
      return 10;
    case SensorKind::force_torque:
      return 6;
    case SensorKind::accelerometer:
    case SensorKind::gyroscope:
      return 3;
    default:
      return 1;
  }
}

}  // namespace wbi
