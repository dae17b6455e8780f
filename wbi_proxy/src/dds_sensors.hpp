// The Sensors element over wbi/<robot>/sensors (encoder velocity and
// acceleration from wbi/<robot>/state: the wire carries no speed sensors).
#pragma once

#include "robot_connection.hpp"
#include "wbi/sensors.hpp"

namespace wbi::proxy {

class DdsSensors final : public wbi::Sensors {
 public:
  explicit DdsSensors(RobotConnection& robot) : robot_(robot) {}

  const IdList& sensor_list(SensorKind kind) const override;
  Stamp read_sensors(SensorKind kind, VectorRef values, ReadMode mode) override;
  Stamp read_sensor(SensorKind kind, int index, VectorRef values, ReadMode mode) override;

 private:
  Stamp read_range(SensorKind kind, int first, int count, VectorRef out, ReadMode mode);
  // Sensors [first, first + count) of `kind` from one sample into out.
  void read_sample(const wbi::msg::SensorSample& sample, SensorKind kind, int first, int count,
                   VectorRef out) const;

  RobotConnection& robot_;
};

}  // namespace wbi::proxy
