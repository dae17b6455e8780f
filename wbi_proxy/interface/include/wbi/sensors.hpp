// The Sensors element: the robot's latest measurements, with their stamps.
#pragma once

#include "wbi/types.hpp"

namespace wbi {

class Sensors {
 public:
  virtual ~Sensors() = default;

  // Names of the sensors of a kind (the controlled joints for joint kinds).
  virtual const IdList& sensor_list(SensorKind kind) const = 0;

  // All sensors of a kind, stacked (see SensorKind for the sizes), or one.
  // Throws StaleDataError when there is no sample, or it is too old.
  virtual Stamp read_sensors(SensorKind kind, VectorRef values,
                             ReadMode mode = ReadMode::latest) = 0;
  virtual Stamp read_sensor(SensorKind kind, int index, VectorRef values,
                            ReadMode mode = ReadMode::latest) = 0;
};

}  // namespace wbi
