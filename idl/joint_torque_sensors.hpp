// Which joints of a robot have a joint-torque sensor, as its description says
// (idl/sensors.idl, SensorSample.joint_torque; idl/description.idl): the joints
// of its JOINT_TORQUE sensors, or every joint when it lists none. A sample with
// an empty joint_torque says, further, that no joint has one.
#pragma once

#include <cstddef>
#include <vector>

#include <wbi/msg/description.h>

namespace wbi::msg {

// [joints] whether each joint of description.joint_names() has a joint-torque sensor.
inline std::vector<bool> joint_torque_sensors(const RobotDescription& description) {
  const auto& names = description.joint_names();
  std::vector<bool> has(names.size(), false);
  bool listed = false;
  for (const auto& sensor : description.sensors()) {
    if (sensor.kind() != SensorKind::JOINT_TORQUE) {
      continue;
    }
    listed = true;
    for (std::size_t j = 0; j < names.size(); ++j) {
      if (names[j] == sensor.name()) {
        has[j] = true;
      }
    }
  }
  if (!listed) {
    has.assign(names.size(), true);
  }
  return has;
}

}  // namespace wbi::msg
