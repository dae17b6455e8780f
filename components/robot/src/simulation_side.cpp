#include "simulation_side.hpp"

#include <wbi/dds/topics.hpp>

#include "messages.hpp"

namespace wbi::robot {

SimulationSide::SimulationSide(dds::Participant& participant, const std::string& robot,
                               actuation::Duration step_period, bool lockstep)
    : robot_(robot),
      ground_truth_(participant, dds::topics::ground_truth(robot), dds::qos::kStream),
      clock_(participant, dds::topics::kClock, dds::qos::kStream) {
  clock_message_.step_ns(step_period.count());
  clock_message_.lockstep(lockstep);
}

void SimulationSide::publish(const actuation::GroundTruth& truth, std::uint64_t tick,
                             actuation::Time stamp) {
  fill_ground_truth(truth, robot_, tick, stamp.count(), truth_message_);
  ground_truth_.publish(truth_message_);
  clock_message_.time_ns(stamp.count());
  clock_message_.tick(tick);
  clock_.publish(clock_message_);
}

}  // namespace wbi::robot
