#include "wbi/sim_models/sensor_noise.hpp"

namespace wbi::sim_models {

SensorNoise::SensorNoise(const robot_config::RobotConfig& config)
    : gaussian_(config.wbi.seed),
      encoders_(config.wbi.encoders),
      encoder_step_(encoder_step(config.wbi.encoders)) {
  for (const auto& imu : config.imus) {
    imus_.push_back({imu.gyro_noise, imu.accel_noise});
  }
  for (const auto& ft : config.force_torque) {
    force_torque_.push_back({ft.force_noise, ft.torque_noise});
  }
}

void SensorNoise::apply(actuation::SensorReadings& r, actuation::Time stamp) {
  Gaussian& noise = gaussian_;
  for (Eigen::Index j = 0; j < r.position.size(); ++j) {
    r.position[j] = quantise(r.position[j] + noise(encoders_.position_noise), encoder_step_);
    r.velocity[j] = r.velocity[j] + noise(encoders_.velocity_noise);
    r.torque[j] = r.torque[j] + noise(encoders_.torque_noise);
  }
  r.joint_stamp = stamp;
  for (std::size_t i = 0; i < r.imus.size(); ++i) {
    auto& imu = r.imus[i];
    for (int a = 0; a < 3; ++a) {
      imu.gyro[a] = imu.gyro[a] + noise(imus_[i].first);
      imu.accel[a] = imu.accel[a] + noise(imus_[i].second);
    }
    imu.stamp = stamp;
  }
  for (std::size_t i = 0; i < r.force_torque.size(); ++i) {
    auto& ft = r.force_torque[i];
    for (int a = 0; a < 3; ++a) {
      ft.wrench[a] = ft.wrench[a] + noise(force_torque_[i].first);
      ft.wrench[a + 3] = ft.wrench[a + 3] + noise(force_torque_[i].second);
    }
    ft.stamp = stamp;
  }
}

}  // namespace wbi::sim_models
