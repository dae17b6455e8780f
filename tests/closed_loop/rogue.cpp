// Test helper: a rogue next to a robot, from a participant named "rogue", at
// 1 kHz until SIGTERM.
//   wbi_test_rogue ROBOT sensors JOINTS
//     well-formed sensor samples for ROBOT (JOINTS encoders, every one at
//     0.5 rad, stamped now) on wbi/<ROBOT>/sensors. Without one producer per
//     stream, an estimator would mix them into the robot's.
//   wbi_test_rogue ROBOT commands JOINT TORQUE
//     well-formed TORQUE commands (controller "rogue") for joint index JOINT on
//     wbi/<ROBOT>/commands. Without joint claims, the robot would apply them.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <thread>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>

namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_signal(int /*signal*/) { stop_requested = true; }

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Calls publish(seq) every millisecond until SIGTERM.
void publish_at_1khz(const std::function<void(std::uint64_t)>& publish) {
  std::cout << "rogue: publishing" << std::endl;
  auto next = std::chrono::steady_clock::now();
  for (std::uint64_t seq = 0; !stop_requested; ++seq) {
    publish(seq);
    next += std::chrono::milliseconds(1);
    std::this_thread::sleep_until(next);
  }
}

void sensors(wbi::dds::Participant& participant, const std::string& robot, std::size_t joints) {
  wbi::dds::Publisher<wbi::msg::SensorSample> publisher(
      participant, wbi::dds::topics::sensors(robot), wbi::dds::qos::kStream);
  wbi::msg::SensorSample sample;
  sample.header().robot(robot);
  sample.encoder_position(std::vector<double>(joints, 0.5));
  publish_at_1khz([&](std::uint64_t seq) {
    sample.header().seq(seq);
    sample.header().stamp_ns(now_ns());
    publisher.publish(sample);
  });
}

void commands(wbi::dds::Participant& participant, const std::string& robot, std::uint16_t joint,
              double torque) {
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> publisher(
      participant, wbi::dds::topics::commands(robot), wbi::dds::qos::kCommand);
  wbi::msg::ActuatorCommand command;
  command.header().robot(robot);
  command.controller("rogue");
  command.joints({joint});
  command.modes({wbi::msg::TORQUE});
  command.references({torque});
  publish_at_1khz([&](std::uint64_t seq) {
    command.header().seq(seq);
    command.header().stamp_ns(now_ns());
    publisher.publish(command);
  });
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 2 ? argv[2] : "";
  if (!(what == "sensors" && argc == 4) && !(what == "commands" && argc == 5)) {
    std::cerr << "usage: wbi_test_rogue ROBOT sensors JOINTS\n"
                 "       wbi_test_rogue ROBOT commands JOINT TORQUE\n";
    return 2;
  }
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  try {
    wbi::dds::Participant participant("rogue");
    if (what == "sensors") {
      sensors(participant, argv[1], static_cast<std::size_t>(std::atol(argv[3])));
    } else {
      commands(participant, argv[1], static_cast<std::uint16_t>(std::atoi(argv[3])),
               std::atof(argv[4]));
    }
  } catch (const std::exception& error) {
    std::cerr << "rogue: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
