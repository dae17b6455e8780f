#include "messages.hpp"

#include <algorithm>

#include <wbi/msg/eigen.hpp>

namespace wbi::robot {

using wbi::msg::to_wire;

void describe(const actuation::BackendDescription& description, const std::string& robot,
              const std::string& source, bool floating_base, bool lockstep,
              wbi::msg::RobotDescription& out) {
  out.header().robot(robot);
  out.floating_base(floating_base);
  out.lockstep(lockstep);
  out.urdf_path(source);
  out.joint_names().clear();
  out.joint_limits().clear();
  for (std::size_t j = 0; j < description.joint_names.size(); ++j) {
    out.joint_names().push_back(description.joint_names[j]);
    wbi::msg::JointLimits limits;
    limits.position_min(description.position_lower[j]);
    limits.position_max(description.position_upper[j]);
    limits.velocity_max(description.velocity_limit[j]);
    limits.effort_max(description.effort_limit[j]);
    out.joint_limits().push_back(limits);
  }
  out.sensors().clear();
  for (std::size_t i = 0; i < description.imu_names.size(); ++i) {
    wbi::msg::SensorInfo info;
    info.name(description.imu_names[i]);
    info.kind(wbi::msg::SensorKind::IMU);
    info.frame(description.imu_frames[i]);
    out.sensors().push_back(info);
  }
  for (std::size_t i = 0; i < description.ft_names.size(); ++i) {
    wbi::msg::SensorInfo info;
    info.name(description.ft_names[i]);
    info.kind(wbi::msg::SensorKind::FORCE_TORQUE);
    info.frame(description.ft_frames[i]);
    out.sensors().push_back(info);
  }
  // Joint-torque sensors are listed only when some joints lack one (idl/description.idl).
  const auto& sensed = description.torque_sensor;
  if (description.any_torque_sensor() &&
      std::find(sensed.begin(), sensed.end(), false) != sensed.end()) {
    for (std::size_t j = 0; j < sensed.size(); ++j) {
      if (sensed[j]) {
        wbi::msg::SensorInfo info;
        info.name(description.joint_names[j]);
        info.kind(wbi::msg::SensorKind::JOINT_TORQUE);
        out.sensors().push_back(info);
      }
    }
  }
}

void prepare_sensor_sample(const actuation::BackendDescription& description,
                           const std::string& robot, wbi::msg::SensorSample& sample) {
  const auto n = description.joint_names.size();
  sample.header().robot(robot);
  sample.encoder_position().assign(n, 0.0);
  // No joint-torque sensor at all: an empty array (idl/sensors.idl).
  sample.joint_torque().assign(description.any_torque_sensor() ? n : 0, 0.0);
  sample.motor_pwm().assign(n, 0.0);
  sample.imus().resize(description.imu_names.size());
  sample.force_torque().resize(description.ft_names.size());
}

void fill_sensor_sample(const actuation::SensorReadings& readings, std::uint64_t tick,
                        std::int64_t stamp_ns, wbi::msg::SensorSample& sample) {
  sample.header().seq(tick);
  sample.header().stamp_ns(stamp_ns);
  to_wire(readings.position, sample.encoder_position());
  if (!sample.joint_torque().empty()) {  // NaN where a joint has no sensor (RobotBackend::read)
    to_wire(readings.torque, sample.joint_torque());
  }
  to_wire(readings.pwm, sample.motor_pwm());
  for (std::size_t i = 0; i < readings.imus.size() && i < sample.imus().size(); ++i) {
    const auto& imu = readings.imus[i];
    auto& out = sample.imus()[i];
    wbi::msg::to_wire_wxyz(imu.orientation, out.orientation());
    to_wire(imu.gyro, out.angular_velocity());
    to_wire(imu.accel, out.linear_acceleration());
  }
  for (std::size_t i = 0; i < readings.force_torque.size() && i < sample.force_torque().size();
       ++i) {
    to_wire(readings.force_torque[i].wrench, sample.force_torque()[i].wrench());
  }
}

void fill_ground_truth(const actuation::GroundTruth& truth, const std::string& robot,
                       std::uint64_t tick, std::int64_t stamp_ns, wbi::msg::GroundTruth& out) {
  out.header().robot(robot);
  out.header().seq(tick);
  out.header().stamp_ns(stamp_ns);
  const auto n = static_cast<Eigen::Index>(truth.tau.size());
  to_wire(truth.q.tail(n), out.q());  // joints come after the base coordinates, if any
  to_wire(truth.nu.tail(n), out.dq());
  to_wire(truth.dnu.tail(n), out.ddq());
  to_wire(truth.base_position, truth.base_orientation, out.base_pose());
  to_wire(truth.base_velocity, out.base_velocity());
  to_wire(truth.base_acceleration, out.base_acceleration());
  out.contact_wrenches().resize(std::min<std::size_t>(truth.contact_wrenches.size(), 16));
  for (std::size_t i = 0; i < out.contact_wrenches().size(); ++i) {
    to_wire(truth.contact_wrenches[i], out.contact_wrenches()[i]);
  }
  to_wire(truth.tau_actuator, out.applied_torque());
  out.push_wrenches().resize(
      std::min<std::size_t>({truth.push_wrenches.size(), truth.push_links.size(), 16}));
  for (std::size_t i = 0; i < out.push_wrenches().size(); ++i) {
    auto& push = out.push_wrenches()[i];
    push.link(truth.push_links[i]);  // a bounded string: no allocation
    to_wire(truth.push_wrenches[i], push.wrench());
  }
}

}  // namespace wbi::robot
