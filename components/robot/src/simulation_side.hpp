// The topics only a simulation has, one sample each per tick: its exact state
// on wbi/<robot>/ground_truth and its time on wbi/clock (the clock that
// components of clock: simulation run on, and that lockstep controllers answer).
// publish() never allocates (buffers sized at construction and first tick).
#pragma once

#include <cstdint>
#include <string>

#include <wbi/msg/sensors.h>
#include <wbi/msg/status.h>
#include <wbi/actuation/simulation_backend.hpp>
#include <wbi/dds/publisher.hpp>

namespace wbi::robot {

class SimulationSide {
 public:
  SimulationSide(dds::Participant& participant, const std::string& robot,
                 actuation::Duration step_period, bool lockstep);

  void publish(const actuation::GroundTruth& truth, std::uint64_t tick, actuation::Time stamp);

 private:
  const std::string robot_;
  wbi::msg::GroundTruth truth_message_;
  wbi::msg::SimulationClock clock_message_;
  dds::Publisher<wbi::msg::GroundTruth> ground_truth_;
  dds::Publisher<wbi::msg::SimulationClock> clock_;
};

}  // namespace wbi::robot
