// Internal: the backend's readings and a simulation's ground truth as wire
// messages. The fill_* functions reuse the messages' buffers (no allocation
// once sized by describe/prepare).
#pragma once

#include <string>

#include <wbi/msg/description.h>
#include <wbi/msg/sensors.h>
#include <wbi/actuation/robot_backend.hpp>
#include <wbi/actuation/simulation_backend.hpp>

namespace wbi::robot {

void describe(const actuation::BackendDescription& description, const std::string& robot,
              const std::string& source, bool floating_base, bool lockstep,
              wbi::msg::RobotDescription& out);

// Sizes the sample's sequences for the backend's joints and sensors.
void prepare_sensor_sample(const actuation::BackendDescription& description,
                           const std::string& robot, wbi::msg::SensorSample& sample);

void fill_sensor_sample(const actuation::SensorReadings& readings, std::uint64_t tick,
                        std::int64_t stamp_ns, wbi::msg::SensorSample& sample);

void fill_ground_truth(const actuation::GroundTruth& truth, const std::string& robot,
                       std::uint64_t tick, std::int64_t stamp_ns, wbi::msg::GroundTruth& out);

}  // namespace wbi::robot
