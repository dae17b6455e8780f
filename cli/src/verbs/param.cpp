// `wbi param list|get|set CONTROLLER [NAME [VALUE...]]`: a hosted
// controller's declared parameters, read and changed while it runs.
#include <iostream>
#include <string>

#include <wbi/controllers/parameter_table.hpp>

#include "../options.hpp"
#include "controller_client.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

std::string range(const msg::ControllerParameter& parameter) {
  std::string text = "[";
  text += controllers::format_values(std::vector<double>{parameter.min()});
  text += ", ";
  text += controllers::format_values(std::vector<double>{parameter.max()});
  text += "]";
  return text;
}

void print_parameter(const msg::ControllerParameter& parameter, bool details) {
  std::cout << parameter.name().to_string() << " = "
            << (parameter.is_text()          ? parameter.text().to_string()
                : parameter.values().empty() ? std::string("(unset)")
                                             : controllers::format_values(parameter.values()));
  if (!parameter.unit().to_string().empty()) {
    std::cout << " " << parameter.unit().to_string();
  }
  if (details) {
    std::cout << "  " << (parameter.is_text() ? std::string("text") : range(parameter))
              << (parameter.live() ? "  live" : "  while inactive") << "  "
              << parameter.help().to_string();
  }
  std::cout << "\n";
}

msg::ControllerReply list_parameters(const Options& options) {
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::LIST_PARAMETERS);
  request.controller(options.get("CONTROLLER"));
  return call_controller_host(options, request, "wbi param");
}

int fail(const char* what, const std::string& error) {
  std::cerr << "wbi param " << what << ": " << error << "\n";
  return kExitError;
}

int run_list(Args args) {
  Options options("wbi param list CONTROLLER --robot NAME [options]",
                  "Lists a controller's parameters: value, unit, range, whether it may change\n"
                  "while the controller is active (live), and what it does.");
  options.positional("CONTROLLER", "a controller of the robot's host (wbi controller list)");
  add_controller_host_options(options);
  if (!options.parse(args)) {
    return kExitOk;
  }
  const auto reply = list_parameters(options);
  if (!reply.error().to_string().empty()) {
    return fail("list", reply.error().to_string());
  }
  for (const auto& parameter : reply.parameters()) {
    print_parameter(parameter, true);
  }
  return kExitOk;
}

int run_get(Args args) {
  Options options("wbi param get CONTROLLER NAME --robot NAME [options]",
                  "Prints one parameter's current value.");
  options.positional("CONTROLLER", "a controller of the robot's host");
  options.positional("NAME", "the parameter");
  add_controller_host_options(options);
  if (!options.parse(args)) {
    return kExitOk;
  }
  const auto reply = list_parameters(options);
  if (!reply.error().to_string().empty()) {
    return fail("get", reply.error().to_string());
  }
  for (const auto& parameter : reply.parameters()) {
    if (parameter.name().to_string() == options.get("NAME")) {
      print_parameter(parameter, false);
      return kExitOk;
    }
  }
  std::string known;
  for (const auto& parameter : reply.parameters()) {
    if (!known.empty()) {
      known += ", ";
    }
    known += parameter.name().to_string();
  }
  return fail("get", options.get("CONTROLLER") + ": no parameter '" + options.get("NAME") +
                         "' (declared: " + known + ")");
}

int run_set(Args args) {
  Options options("wbi param set CONTROLLER NAME VALUE... --robot NAME [options]",
                  "Sets a parameter; the host applies it between two ticks and answers once it\n"
                  "has. A value out of range, of the wrong size, or a parameter that cannot\n"
                  "change while its controller is active is refused with one line.");
  options.positional("CONTROLLER", "a controller of the robot's host");
  options.positional("NAME", "the parameter");
  options.rest("VALUE", "the value (one per joint for a per-joint parameter)");
  add_controller_host_options(options);
  if (!options.parse(args)) {
    return kExitOk;
  }
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::SET_PARAMETER);
  request.controller(options.get("CONTROLLER"));
  request.parameter(options.get("NAME"));
  if (options.rest_values().empty()) {
    throw UsageError("give the value after the parameter's name");
  }
  for (const auto& text : options.rest_values()) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size()) {
      // Not a number: the value of a text parameter (a frame name), when alone.
      if (options.rest_values().size() != 1) {
        throw UsageError("value '" + text + "' is not a number");
      }
      request.text(text);
      request.values().clear();
      break;
    }
    request.values().push_back(value);
  }
  const auto reply = call_controller_host(options, request, "wbi param");
  if (!reply.error().to_string().empty()) {
    return fail("set", "refused: " + reply.error().to_string());
  }
  std::cout << reply.text().to_string() << "\n";
  return kExitOk;
}

}  // namespace

int run_param(Args args) {
  const std::string usage =
      "usage: wbi param {list,get,set} CONTROLLER [NAME [VALUE...]] --robot NAME [--help]\n\n"
      "  list   a controller's parameters, with unit, range and whether they are live\n"
      "  get    one parameter's value\n"
      "  set    change a parameter while the controller runs\n";
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::cout << usage;
    return args.empty() ? kExitError : kExitOk;
  }
  if (args[0] == "list") {
    return run_list(args.subspan(1));
  }
  if (args[0] == "get") {
    return run_get(args.subspan(1));
  }
  if (args[0] == "set") {
    return run_set(args.subspan(1));
  }
  throw UsageError("unknown sub-command '" + args[0] + "' (list, get, set)");
}

}  // namespace wbi::cli
