// The topics only a simulation has, one sample each per tick: its exact state
// on wbi/<robot>/ground_truth and its time on wbi/clock (the clock that
// components of clock: simulation run on, and that lockstep controllers answer).
// publish() never allocates (buffers sized at construction and first tick).
//
// With a ground-truth file (`ground_truth_file`), every tick's GroundTruth is
// also written to an MCAP file, the sample as published (CDR, channel
// wbi/<robot>/ground_truth), log and publish time its simulated stamp: no wall
// clock, so two lockstep runs that are the same give the same bytes. Unlike a
// `wbi record` beside the run it loses no tick (the loop writes it). After its
// first chunk a tick's write does not allocate (wbi/mcap/writer.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <wbi/msg/sensors.h>
#include <wbi/msg/status.h>
#include <wbi/actuation/simulation_backend.hpp>
#include <wbi/dds/publisher.hpp>

namespace wbi::robot {

class GroundTruthFile;

class SimulationSide {
 public:
  // ground_truth_file: empty for none. Throws std::runtime_error naming the
  // file when it cannot be created.
  SimulationSide(dds::Participant& participant, const std::string& robot,
                 actuation::Duration step_period, bool lockstep,
                 const std::string& ground_truth_file = {});
  ~SimulationSide();

  void publish(const actuation::GroundTruth& truth, std::uint64_t tick, actuation::Time stamp);
  // Completes the ground-truth file (its summary written, closed); no more
  // ticks are written to it. The loop's thread, once stepping ended.
  void close_file();

 private:
  const std::string robot_;
  wbi::msg::GroundTruth truth_message_;
  wbi::msg::SimulationClock clock_message_;
  dds::Publisher<wbi::msg::GroundTruth> ground_truth_;
  dds::Publisher<wbi::msg::SimulationClock> clock_;
  std::unique_ptr<GroundTruthFile> file_;
};

}  // namespace wbi::robot
