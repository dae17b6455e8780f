// `wbi controller list|switch`: the controllers a robot's controller host
// runs, and switching between them at one tick boundary.
#include <iostream>
#include <string>

#include "../options.hpp"
#include "controller_client.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

void print_controllers(const msg::ControllerReply& reply) {
  for (const auto& controller : reply.controllers()) {
    std::cout << (controller.active() ? "* " : "  ") << controller.name().to_string() << "  ["
              << controller.type().to_string() << "]"
              << (controller.active() ? "  active" : "  inactive");
    if (!controller.configure_error().to_string().empty()) {
      std::cout << "  (cannot run: " << controller.configure_error().to_string() << ")";
    }
    std::cout << "\n";
  }
}

int run_list(Args args) {
  Options options("wbi controller list --robot NAME [options]",
                  "Lists the controllers of the robot's controller host; * marks the active one.");
  add_controller_host_options(options);
  if (!options.parse(args)) {
    return kExitOk;
  }
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::LIST_CONTROLLERS);
  const auto reply = call_controller_host(options, request, "wbi controller");
  if (!reply.error().to_string().empty()) {
    std::cerr << "wbi controller list: " << reply.error().to_string() << "\n";
    return kExitError;
  }
  print_controllers(reply);
  return kExitOk;
}

int run_switch(Args args) {
  Options options(
      "wbi controller switch --robot NAME --activate A --deactivate B [options]",
      "Deactivates B and activates A at one tick boundary, or refuses the switch whole\n"
      "(an unknown name, B not active, A not configured) and changes nothing. Prints\n"
      "when it took effect and the joint-torque step it made.");
  options.option("activate", "NAME", "the controller to activate");
  options.option("deactivate", "NAME", "the controller to deactivate (the active one)");
  add_controller_host_options(options);
  if (!options.parse(args)) {
    return kExitOk;
  }
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::SWITCH_CONTROLLERS);
  if (const auto name = options.get_optional("activate")) {
    request.activate().push_back(*name);
  }
  if (const auto name = options.get_optional("deactivate")) {
    request.deactivate().push_back(*name);
  }
  if (request.activate().empty() && request.deactivate().empty()) {
    throw UsageError("give --activate NAME and/or --deactivate NAME");
  }
  const auto reply = call_controller_host(options, request, "wbi controller");
  if (!reply.error().to_string().empty()) {
    std::cerr << "wbi controller switch: refused: " << reply.error().to_string() << "\n";
    return kExitError;
  }
  std::cout << "switched " << reply.text().to_string() << "\n";
  return kExitOk;
}

}  // namespace

int run_controller(Args args) {
  const std::string usage =
      "usage: wbi controller {list,switch} [--help]\n\n"
      "  list     the controllers of a robot's controller host\n"
      "  switch   activate one and deactivate another at one tick boundary\n";
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::cout << usage;
    return args.empty() ? kExitError : kExitOk;
  }
  if (args[0] == "list") {
    return run_list(args.subspan(1));
  }
  if (args[0] == "switch") {
    return run_switch(args.subspan(1));
  }
  throw UsageError("unknown sub-command '" + args[0] + "' (list, switch)");
}

}  // namespace wbi::cli
