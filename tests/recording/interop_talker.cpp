// Test helper of test_record_interop: once each of its topics has a
// subscriber, publishes the robot description of interop_pattern.hpp on
// wbi/<ROBOT>/description, then COUNT sensor samples and COUNT state
// estimates on wbi/<ROBOT>/sensors and wbi/<ROBOT>/state, each acknowledged
// before the next (none lost to a writer's bounded history); exits 0.
// usage: wbi_test_interop_talker ROBOT COUNT
#include <chrono>
#include <cstdlib>
#include <iostream>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>

#include "interop_pattern.hpp"

namespace {

template <class T>
bool deliver(wbi::dds::Publisher<T>& publisher, const T& sample) {
  return publisher.publish(sample) && publisher.wait_acknowledged(std::chrono::seconds(5));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 || std::atol(argv[2]) <= 0) {
    std::cerr << "usage: wbi_test_interop_talker ROBOT COUNT (COUNT > 0)\n";
    return 2;
  }
  const std::string robot = argv[1];
  const auto count = static_cast<std::uint64_t>(std::atol(argv[2]));
  namespace dds = wbi::dds;
  dds::Participant participant("interop talker");
  // Transient local: a reader whose side of the match comes after the first write still gets it.
  dds::Publisher<wbi::msg::RobotDescription> description(
      participant, dds::topics::description(robot), dds::qos::kLatched);
  dds::Publisher<wbi::msg::SensorSample> sensors(participant, dds::topics::sensors(robot),
                                                 dds::qos::kLatched);
  dds::Publisher<wbi::msg::StateEstimate> state(participant, dds::topics::state(robot),
                                                dds::qos::kLatched);
  const auto wait = std::chrono::seconds(20);
  if (!description.wait_for_subscribers(1, wait) || !sensors.wait_for_subscribers(1, wait) ||
      !state.wait_for_subscribers(1, wait)) {
    std::cerr << "interop talker: not every topic has a subscriber within 20 s\n";
    return 1;
  }
  wbi::msg::RobotDescription description_sample;
  wbi::test::fill_description(description_sample, robot);
  if (!deliver(description, description_sample)) {
    std::cerr << "interop talker: description not delivered\n";
    return 1;
  }
  wbi::msg::SensorSample sensor_sample;
  wbi::msg::StateEstimate state_sample;
  for (std::uint64_t seq = 0; seq < count; ++seq) {
    wbi::test::fill_sensors(sensor_sample, robot, seq);
    wbi::test::fill_state(state_sample, robot, seq);
    if (!deliver(sensors, sensor_sample) || !deliver(state, state_sample)) {
      std::cerr << "interop talker: sample " << seq << " not delivered\n";
      return 1;
    }
  }
  std::cout << "interop talker: done" << std::endl;
  return 0;
}
