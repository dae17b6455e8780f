// Test helper: publishes COUNT pattern sensor samples on wbi/<ROBOT>/sensors
// once a subscriber has matched, each acknowledged before the next (so none
// is lost to the writer's bounded history), and exits 0. With COUNT = 0 it
// publishes at 100 Hz on the wbi.stream profile until SIGTERM, and has a
// writer of commands too (wbi.command), so that a test can see which QoS
// each profile got (WBI_QOS_FILE). With `burst`, it publishes COUNT samples on
// wbi.stream once a subscriber matched: the first one acknowledged (the reader
// then knows the writer: a sample sent before is not its to lose), the rest
// back to back (the writer keeps only the newest: a reader that falls behind
// loses some). It then says "talker: done" with the writes DDS refused, and
// stays until SIGTERM, so that its writer can still tell the reader what it lost.
// usage: wbi_test_talker ROBOT COUNT [burst]
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

#include <optional>

#include <wbi/msg/commands.h>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>

#include "sample_pattern.hpp"

namespace {
std::atomic<bool> stop_requested{false};
extern "C" void on_signal(int /*signal*/) { stop_requested = true; }
}  // namespace

int main(int argc, char** argv) {
  const bool burst = argc == 4 && std::string(argv[3]) == "burst";
  if (argc != 3 && !burst) {
    std::cerr << "usage: wbi_test_talker ROBOT COUNT [burst]\n";
    return 2;
  }
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  const std::string robot = argv[1];
  const long count = std::atol(argv[2]);
  std::optional<wbi::dds::Participant> created;
  try {
    created.emplace("talker");
  } catch (const std::exception& error) {
    std::cerr << "talker: " << error.what() << "\n";
    return 1;
  }
  wbi::dds::Participant& participant = *created;
  wbi::dds::Publisher<wbi::msg::SensorSample> publisher(
      participant, wbi::dds::topics::sensors(robot),
      // Counted: transient local, so that a reader whose side of the match comes
      // after the first write still gets that sample (a volatile one would not).
      count > 0 && !burst ? wbi::dds::qos::kLatched : wbi::dds::qos::kStream);
  std::cout << "talker: ready" << std::endl;
  wbi::msg::SensorSample sample;
  if (count > 0) {
    if (!publisher.wait_for_subscribers(1, std::chrono::seconds(20))) {
      std::cerr << "talker: no subscriber within 20 s\n";
      return 1;
    }
    if (burst) {
      long refused = 0;
      for (long seq = 0; seq < count; ++seq) {
        wbi::test::fill_pattern(sample, robot, static_cast<std::uint64_t>(seq));
        refused += publisher.publish(sample) ? 0 : 1;
        if (seq == 0 && !publisher.wait_acknowledged(std::chrono::seconds(15))) {
          std::cerr << "talker: the first sample was not acknowledged\n";
          return 1;
        }
      }
      std::cout << "talker: done, " << refused << " writes refused" << std::endl;
      while (!stop_requested) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));  // polls the signal flag
      }
      return 0;
    }
    for (long seq = 0; seq < count && !stop_requested; ++seq) {
      wbi::test::fill_pattern(sample, robot, static_cast<std::uint64_t>(seq));
      // 15 s (the listener of test_dds_transport waits 20 s for ten): once in an
      // ASan CI run, a talker started after two SIGKILLed ones over shared
      // memory had its first sample received but not acknowledged within 5 s
      // (not reproduced in 20 runs); Fast DDS recovers a port left locked by a
      // killed process only after its health check.
      if (!publisher.publish(sample) || !publisher.wait_acknowledged(std::chrono::seconds(15))) {
        std::cerr << "talker: sample " << seq << " not delivered\n";
        return 1;
      }
    }
    std::cout << "talker: done" << std::endl;
    return 0;
  }
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(
      participant, wbi::dds::topics::commands(robot), wbi::dds::qos::kCommand);
  for (std::uint64_t seq = 0; !stop_requested; ++seq) {
    wbi::test::fill_pattern(sample, robot, seq);
    publisher.publish(sample);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return 0;
}
