// The sensor side of a robot on DDS: publishes the robot description (latched,
// once) and, every tick, the backend's readings as a SensorSample stamped with
// the readings' source stamp and a sequence number. One implementation, used by
// sim_robot and by the driver component (wbi/robot/robot_driver.hpp).
// publish() never allocates (buffers sized at construction).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <wbi/msg/description.h>
#include <wbi/msg/sensors.h>
#include <wbi/actuation/robot_backend.hpp>
#include <wbi/dds/publisher.hpp>

namespace wbi::robot {

class SensorSide {
 public:
  // source: where the description came from (URDF or config path), for the
  // description's urdf_path field.
  SensorSide(dds::Participant& participant, const std::string& robot,
             const actuation::BackendDescription& description, const std::string& source,
             bool floating_base, bool lockstep);

  // Publishes one sample: header.seq = seq, header.stamp_ns = stamp_ns.
  void publish(const actuation::SensorReadings& readings, std::uint64_t seq, std::int64_t stamp_ns);

 private:
  wbi::msg::RobotDescription description_message_;
  wbi::msg::SensorSample sample_;
  dds::Publisher<wbi::msg::RobotDescription> description_;
  dds::Publisher<wbi::msg::SensorSample> sensors_;
};

}  // namespace wbi::robot
