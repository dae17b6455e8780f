// Test helper: a rogue next to a robot. Publishes well-formed sensor samples
// for ROBOT (JOINTS encoders, every one at 0.5 rad, stamped now) at 1 kHz on
// wbi/<ROBOT>/sensors from a participant named "rogue", until SIGTERM. Without
// one producer per stream, an estimator would mix them into the robot's.
// usage: wbi_test_rogue_sensors ROBOT JOINTS
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <thread>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>

namespace {
std::atomic<bool> stop_requested{false};
extern "C" void on_signal(int /*signal*/) { stop_requested = true; }
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: wbi_test_rogue_sensors ROBOT JOINTS\n";
    return 2;
  }
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  const std::string robot = argv[1];
  const auto joints = static_cast<std::size_t>(std::atol(argv[2]));
  try {
    wbi::dds::Participant participant("rogue");
    wbi::dds::Publisher<wbi::msg::SensorSample> publisher(
        participant, wbi::dds::topics::sensors(robot), wbi::dds::qos::kStream);
    wbi::msg::SensorSample sample;
    sample.header().robot(robot);
    sample.encoder_position(std::vector<double>(joints, 0.5));
    std::cout << "rogue: publishing" << std::endl;
    auto next = std::chrono::steady_clock::now();
    for (std::uint64_t seq = 0; !stop_requested; ++seq) {
      sample.header().seq(seq);
      sample.header().stamp_ns(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count());
      publisher.publish(sample);
      next += std::chrono::milliseconds(1);
      std::this_thread::sleep_until(next);
    }
  } catch (const std::exception& error) {
    std::cerr << "rogue: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
