// `wbi launch FILE`: runs the processes of a deploy file (see deploy/README.md).
#include <iostream>
#include <ostream>
#include <set>
#include <string>

#include <wbi/launch/launcher.hpp>
#include <wbi/vocabulary/joined_names.hpp>

#include "../join_options.hpp"
#include "../options.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

// `--list`: what scripts take from a deploy file (scripts/wbi-security-setup),
// through this one reader instead of a YAML parser of their own.
void print_processes(const wbi::deploy::DeployFile& deploy, std::ostream& out) {
  const auto joined = [](const std::set<std::string>& names) {
    std::string text;
    for (const auto& name : names) {
      text += (text.empty() ? "" : ",") + name;
    }
    return text.empty() ? std::string("-") : text;
  };
  for (const auto& process : deploy.processes) {
    std::set<std::string> types;
    std::set<std::string> robots;
    for (const auto& component : process.component_nodes) {
      if (const auto type = component["type"]; type && type.IsScalar()) {
        types.insert(type.as<std::string>());
      }
      if (const auto robot = component["parameters"]["robot"]; robot && robot.IsScalar()) {
        robots.insert(robot.as<std::string>());
      }
    }
    out << process.name << '\t' << joined(types) << '\t' << joined(robots) << '\n';
  }
}

}  // namespace

int run_launch(Args args) {
  Options options("wbi launch FILE [options]",
                  "Starts the processes of a deploy file, each once the topics it waits for\n"
                  "exist; prefixes their output with their name; restarts them by their\n"
                  "respawn policy; stops them all on Ctrl-C/SIGTERM (SIGKILL after the grace\n"
                  "period), after --duration, or when a required process fails. A process\n"
                  "that ends with 78 (configuration error) or 65 (its run failed its checks) is\n"
                  "never respawned; one whose start stalled (75) is started again at once.\n"
                  "Exits 0 when every process did its part; 1 when any failed (even an optional\n"
                  "one), never came up, or had to be killed (the summary names each); 130 when\n"
                  "interrupted.");
  options.positional("FILE", "deploy file (YAML)");
  options.option("duration", "SECONDS", "stop everything after this long (0: no limit)", "0");
  options.option("grace", "SECONDS", "time between SIGTERM and SIGKILL when stopping", "5");
  options.flag("one-process",
               "host every process's components in one wbi_host (file order), for speed: no "
               "waits for topics, no respawns; not for secured deployments");
  options.option("process", "NAME[,NAME...]",
                 "start only these processes (this host's part; the others run on other "
                 "hosts and are waited for by their topics as usual)");
  options.flag("list",
               "print the file's processes and exit, one line each: NAME, the component types "
               "it hosts and the robots they name (comma-separated, '-' for none), tab-separated");
  // Above the file's blocks and the environment, for every process started.
  add_join_options(options, false);
  options.example("wbi launch deploy/demo.yaml --duration 8",
                  "the demo: PD + gravity compensation moves the simulated arm, for 8 s");
  options.example("wbi launch deploy/arm_controller_host.yaml",
                  "the arm under a controller host, to drive with wbi controller and wbi param");
  options.example("wbi launch deploy/demo.yaml --one-process --duration 8",
                  "the same demo, every process's components in one wbi_host");
  if (!options.parse(args)) {
    return kExitOk;
  }
  launch::LaunchOptions launch_options;
  launch_options.duration_s = options.get_double("duration");
  launch_options.stop_grace_s = options.get_double("grace");
  launch_options.join = join_flags(options);
  if (launch_options.duration_s < 0 || launch_options.stop_grace_s < 0) {
    throw UsageError("--duration and --grace must be >= 0");
  }
  auto deploy = wbi::deploy::read_deploy_file(options.get("FILE"));
  if (const auto processes = options.get_optional("process"); processes) {
    deploy = launch::only_processes(std::move(deploy), split_names(*processes, ','));
  }
  if (options.has("list")) {
    print_processes(deploy, std::cout);
    return kExitOk;
  }
  if (options.has("one-process")) {
    if (launch_options.join.security_directory) {
      throw UsageError("--one-process: a secured deployment gives each process its own identity");
    }
    deploy = launch::in_one_process(std::move(deploy));
  }
  // A bad plugin is refused before anything starts (one line, exit 1).
  launch::check_plugins(deploy);
  return launch::run_launch(deploy, launch_options, std::cout);
}

}  // namespace wbi::cli
