// SensorNoise: what a simulated sensor adds to the truth — Gaussian noise of
// the robot config's σ (encoders, IMUs, F/T) and the encoders' quantisation —
// drawn from one generator seeded by `wbi.seed` in a fixed order (each joint:
// position, velocity, torque; each IMU: gyro then accelerometer, axis by axis;
// each F/T: force then torque, axis by axis). An engine fills in the true values
// and this makes them readings, so that every engine reads the same for the
// same truth. Nothing allocates.
#pragma once

#include <vector>

#include "wbi/actuation/robot_backend.hpp"
#include "wbi/robot_config/robot_config.hpp"
#include "wbi/sim_models/sensor_actuator_models.hpp"

namespace wbi::sim_models {

class SensorNoise {
 public:
  explicit SensorNoise(const robot_config::RobotConfig& config);

  // `readings` holds the true values (sized for the config's sensors): adds the
  // noise, quantises the encoder positions, stamps every reading with `stamp`.
  void apply(actuation::SensorReadings& readings, actuation::Time stamp);

 private:
  struct Sigma {
    double first = 0.0, second = 0.0;  // IMU: gyro, accel; F/T: force, torque
  };
  Gaussian gaussian_;
  robot_config::EncoderConfig encoders_;
  double encoder_step_ = 0.0;
  std::vector<Sigma> imus_, force_torque_;
};

}  // namespace wbi::sim_models
