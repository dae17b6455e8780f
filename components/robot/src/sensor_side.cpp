#include "sensor_side.hpp"

#include <wbi/dds/topics.hpp>

#include "messages.hpp"

namespace wbi::robot {

SensorSide::SensorSide(dds::Participant& participant, const std::string& robot,
                       const actuation::BackendDescription& description, const std::string& source,
                       bool floating_base, bool lockstep)
    : description_(participant, dds::topics::description(robot), dds::qos::kLatched),
      sensors_(participant, dds::topics::sensors(robot), dds::qos::kStream) {
  describe(description, robot, source, floating_base, lockstep, description_message_);
  description_.publish(description_message_);
  prepare_sensor_sample(description, robot, sample_);
}

void SensorSide::publish(const actuation::SensorReadings& readings, std::uint64_t seq,
                         std::int64_t stamp_ns) {
  fill_sensor_sample(readings, seq, stamp_ns, sample_);
  sensors_.publish(sample_);
}

}  // namespace wbi::robot
