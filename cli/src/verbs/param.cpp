// `wbi param list|get|set CONTROLLER [NAME [VALUE...]]`: a hosted
// controller's declared parameters, read and changed while it runs.
#include <iostream>
#include <string>

#include <wbi/controllers/parameter_table.hpp>
#include <wbi/types.hpp>

#include "../options.hpp"
#include "../subcommands.hpp"
#include "controller_client.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

std::string range(const controllers::ParameterInfo& parameter) {
  std::string text = "[";
  text += controllers::format_values(std::vector<double>{parameter.min});
  text += ", ";
  text += controllers::format_values(std::vector<double>{parameter.max});
  text += "]";
  return text;
}

void print_parameter(const controllers::ParameterInfo& parameter, bool details) {
  std::cout << parameter.name << " = "
            << (parameter.is_text          ? parameter.text
                : parameter.values.empty() ? std::string("(unset)")
                                           : controllers::format_values(parameter.values));
  if (!parameter.unit.empty()) {
    std::cout << " " << parameter.unit;
  }
  if (details) {
    std::cout << "  " << (parameter.is_text ? std::string("text") : range(parameter))
              << (parameter.live ? "  live" : "  while inactive") << "  " << parameter.help;
  }
  std::cout << "\n";
}

// Against `wbi launch deploy/arm_controller_host.yaml` (no --robot: the only robot).
constexpr const char* kListExample = "wbi param list pd";
constexpr const char* kGetExample = "wbi param get pd gain_scale";
constexpr const char* kSetExample = "wbi param set pd gain_scale 0.5";

int refused(const char* what, const Error& refusal) {
  std::cerr << "wbi param " << what << ": " << refusal.what() << "\n";
  return kExitError;
}

int run_list(Args args) {
  Options options("wbi param list CONTROLLER [--robot NAME] [options]",
                  "Lists a controller's parameters: value, unit, range, whether it may change\n"
                  "while the controller is active (live), and what it does.");
  options.positional("CONTROLLER", "a controller of the robot's host (wbi controller list)");
  add_controller_host_options(options);
  options.example(kListExample,
                  "the parameters of controller pd (wbi launch deploy/arm_controller_host.yaml)");
  options.example("wbi param list hold --robot arm", "of hold, naming the robot");
  if (!options.parse(args)) {
    return kExitOk;
  }
  HostConnection host(options, "wbi param");
  try {
    for (const auto& parameter : host.client->parameters(options.get("CONTROLLER"))) {
      print_parameter(parameter, true);
    }
  } catch (const Error& refusal) {
    return refused("list", refusal);
  }
  return kExitOk;
}

int run_get(Args args) {
  Options options("wbi param get CONTROLLER NAME [--robot NAME] [options]",
                  "Prints one parameter's current value.");
  options.positional("CONTROLLER", "a controller of the robot's host");
  options.positional("NAME", "the parameter");
  add_controller_host_options(options);
  options.example(kGetExample, "pd's gain scale");
  if (!options.parse(args)) {
    return kExitOk;
  }
  HostConnection host(options, "wbi param");
  std::string known;
  try {
    for (const auto& parameter : host.client->parameters(options.get("CONTROLLER"))) {
      if (parameter.name == options.get("NAME")) {
        print_parameter(parameter, false);
        return kExitOk;
      }
      known += known.empty() ? "" : ", ";
      known += parameter.name;
    }
  } catch (const Error& refusal) {
    return refused("get", refusal);
  }
  return refused("get", Error(options.get("CONTROLLER") + ": no parameter '" + options.get("NAME") +
                              "' (declared: " + known + ")"));
}

int run_set(Args args) {
  Options options("wbi param set CONTROLLER NAME VALUE... [--robot NAME] [options]",
                  "Sets a parameter; the host applies it between two ticks and answers once it\n"
                  "has. A value out of range, of the wrong size, or a parameter that cannot\n"
                  "change while its controller is active is refused with one line.");
  options.positional("CONTROLLER", "a controller of the robot's host");
  options.positional("NAME", "the parameter");
  options.rest("VALUE", "the value (one per joint for a per-joint parameter)");
  add_controller_host_options(options);
  options.example(kSetExample, "halve pd's gains while it runs");
  options.example("wbi param set pd target 0 0.5 0 1 0 0.5 0",
                  "a new target posture, one value per joint (reached in transition_s)");
  if (!options.parse(args)) {
    return kExitOk;
  }
  if (options.rest_values().empty()) {
    throw UsageError("give the value after the parameter's name");
  }
  std::vector<double> values;
  for (const auto& text : options.rest_values()) {
    std::size_t used = 0;
    try {
      values.push_back(std::stod(text, &used));
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size()) {
      throw UsageError("value '" + text + "' is not a number");
    }
  }
  HostConnection host(options, "wbi param");
  try {
    std::cout << host.client->set_parameter(options.get("CONTROLLER"), options.get("NAME"), values)
              << "\n";
  } catch (const Error& refusal) {
    std::cerr << "wbi param set: refused: " << refusal.what() << "\n";
    return kExitError;
  }
  return kExitOk;
}

}  // namespace

int run_param(Args args) {
  return run_subcommand(
      "param", args,
      {
          {"list", "a controller's parameters, with unit, range and whether they are live",
           kListExample, run_list},
          {"get", "one parameter's value", kGetExample, run_get},
          {"set", "change a parameter while the controller runs", kSetExample, run_set},
      },
      kWhichRobotNote);
}

}  // namespace wbi::cli
