// Uses the installed wbi: publishes a sensor sample and reads it back.
#include <chrono>
#include <iostream>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

int main() {
  wbi::dds::Participant participant("consumer");
  wbi::dds::Publisher<wbi::msg::SensorSample> publisher(
      participant, wbi::dds::topics::sensors("consumer"), wbi::dds::qos::kCommand);
  wbi::dds::Subscriber<wbi::msg::SensorSample> subscriber(
      participant, wbi::dds::topics::sensors("consumer"), wbi::dds::qos::kCommand);
  if (!publisher.wait_for_subscribers(1, std::chrono::seconds(10))) {
    std::cerr << "consumer: no match\n";
    return 1;
  }
  wbi::msg::SensorSample sample;
  sample.encoder_position({0.5, 1.5});
  publisher.publish(sample);
  wbi::dds::Received<wbi::msg::SensorSample> got;
  if (!subscriber.wait_newer(got, 0, std::chrono::seconds(10)) ||
      got.sample.encoder_position().size() != 2) {
    std::cerr << "consumer: sample lost\n";
    return 1;
  }
  std::cout << "consumer: ok\n";
  return 0;
}
