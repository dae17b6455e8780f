// `wbi controller list|switch`: the controllers a robot's controller host
// runs, and switching between them at one tick boundary.
#include <iostream>
#include <string>

#include <wbi/types.hpp>

#include "../options.hpp"
#include "../subcommands.hpp"
#include "controller_client.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

// Against `wbi launch deploy/arm_controller_host.yaml` (no --robot: the only robot).
constexpr const char* kListExample = "wbi controller list";
constexpr const char* kSwitchExample = "wbi controller switch --activate hold --deactivate pd";

int run_list(Args args) {
  Options options("wbi controller list [--robot NAME] [options]",
                  "Lists the controllers of the robot's controller host; * marks the active one.");
  add_controller_host_options(options);
  options.example(kListExample,
                  "the only robot's controllers (wbi launch "
                  "deploy/arm_controller_host.yaml)");
  options.example("wbi controller list --robot arm --deploy deploy/arm_controller_host.yaml",
                  "the arm's, joining the deployment as its file says (domain, network)");
  if (!options.parse(args)) {
    return kExitOk;
  }
  HostConnection host(options, "wbi controller");
  for (const auto& controller : host.client->list()) {
    std::cout << (controller.active ? "* " : "  ") << controller.name << "  [" << controller.type
              << "]" << (controller.active ? "  active" : "  inactive");
    if (!controller.configure_error.empty()) {
      std::cout << "  (cannot run: " << controller.configure_error << ")";
    }
    std::cout << "\n";
  }
  return kExitOk;
}

int run_switch(Args args) {
  Options options(
      "wbi controller switch --activate A --deactivate B [--robot NAME] [options]",
      "Deactivates B and activates A at one tick boundary, or refuses the switch whole\n"
      "(an unknown name, B not active, A not configured) and changes nothing. Prints\n"
      "when it took effect and the joint-torque step it made.");
  options.option("activate", "NAME", "the controller to activate");
  options.option("deactivate", "NAME", "the controller to deactivate (the active one)");
  add_controller_host_options(options);
  options.example(kSwitchExample, "from pd to hold, at one tick");
  options.example("wbi controller switch --activate pd --deactivate hold --robot arm",
                  "and back, naming the robot");
  if (!options.parse(args)) {
    return kExitOk;
  }
  const std::string activate = options.get_optional("activate").value_or("");
  const std::string deactivate = options.get_optional("deactivate").value_or("");
  if (activate.empty() && deactivate.empty()) {
    throw UsageError("give --activate NAME and/or --deactivate NAME");
  }
  HostConnection host(options, "wbi controller");
  try {
    std::cout << "switched " << host.client->switch_controllers(activate, deactivate) << "\n";
  } catch (const Error& refusal) {
    std::cerr << "wbi controller switch: refused: " << refusal.what() << "\n";
    return kExitError;
  }
  return kExitOk;
}

}  // namespace

int run_controller(Args args) {
  return run_subcommand(
      "controller", args,
      {
          {"list", "the controllers of a robot's controller host", kListExample, run_list},
          {"switch", "activate one and deactivate another at one tick boundary", kSwitchExample,
           run_switch},
      },
      kWhichRobotNote);
}

}  // namespace wbi::cli
