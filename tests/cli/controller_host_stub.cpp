// Test helper: answers the controller service of each ROBOT
// (wbi/<ROBOT>/controllers, idl/controllers.idl) as a controller host would
// whose one controller `stub` (type `stub`, active) has one parameter `gain`
// = 1: list and read only, without a robot or a control loop. So that tests of
// `wbi controller` and `wbi param` can put one, two or no hosts on their
// domain cheaply. Prints "stub: ready" once serving; runs until SIGTERM/SIGINT.
// usage: wbi_test_controller_host ROBOT...
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <list>
#include <string>
#include <thread>

#include <wbi/msg/controllers.h>
#include <wbi/dds/server.hpp>
#include <wbi/dds/topics.hpp>

namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_signal(int /*signal*/) { stop_requested = true; }

using Service = wbi::dds::Server<wbi::msg::ControllerRequest, wbi::msg::ControllerReply>;

void answer(const std::string& robot, const wbi::msg::ControllerRequest& request,
            wbi::msg::ControllerReply& reply) {
  reply.error("");
  reply.text("");
  reply.controllers().clear();
  reply.parameters().clear();
  if (request.robot().to_string() != robot) {
    reply.error("this host controls robot '" + robot + "', not '" + request.robot().to_string() +
                "'");
  } else if (request.action() == wbi::msg::ControllerAction::LIST_CONTROLLERS) {
    wbi::msg::HostedController stub;
    stub.name("stub");
    stub.type("stub");
    stub.active(true);
    reply.controllers().push_back(stub);
  } else if (request.action() == wbi::msg::ControllerAction::LIST_PARAMETERS) {
    wbi::msg::ControllerParameter gain;
    gain.controller("stub");
    gain.name("gain");
    gain.max(10.0);
    gain.live(true);
    gain.values().push_back(1.0);
    reply.parameters().push_back(gain);
  } else {
    reply.error("the stub host of '" + robot + "' only lists its controllers and parameters");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: wbi_test_controller_host ROBOT...\n";
    return 2;
  }
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  try {
    wbi::dds::Participant participant("controller host stub");
    std::list<Service> services;  // a Server is neither copied nor moved
    for (int i = 1; i < argc; ++i) {
      const std::string robot = argv[i];
      services.emplace_back(
          participant, wbi::dds::topics::controller_service(robot),
          [robot](const auto& request, auto& reply) { answer(robot, request, reply); });
    }
    std::cout << "stub: ready" << std::endl;
    while (!stop_requested) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));  // polls the signal flag
    }
  } catch (const std::exception& error) {
    std::cerr << "stub: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
