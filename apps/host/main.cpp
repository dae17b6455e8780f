// wbi_host FILE.yaml: runs the components a host file lists (see
// wbi/runtime/host.hpp) in this process until SIGINT or SIGTERM, then stops
// them cleanly (deactivate, cleanup, shutdown, in reverse order); started by
// `wbi launch`, also when the launcher dies. Its types come from plugins: the
// built-in one, then those the file names (`plugins:`, wbi/runtime/plugins.hpp).
// Exit codes: 0 after SIGTERM, 130 after SIGINT, 78 on a configuration error
// (bad command line, file, plugin, type or parameter: `wbi launch` does not
// respawn it), 1 on another error (one line on stderr); a component that ends
// the process (wbi/runtime/process_exit.hpp) gives its code.
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <pthread.h>
#include <yaml-cpp/yaml.h>

#include <wbi/catalog.hpp>
#include <wbi/dds/participant.hpp>
#include <wbi/deploy/placement.hpp>
#include <wbi/deploy/process_host.hpp>
#include <wbi/launch/launcher.hpp>
#include <wbi/runtime/console_line.hpp>
#include <wbi/runtime/handshake_watch.hpp>
#include <wbi/runtime/host.hpp>
#include <wbi/runtime/parameters.hpp>
#include <wbi/runtime/plugins.hpp>
#include <wbi/runtime/process_exit.hpp>
#include <wbi/runtime/runner.hpp>

namespace {

struct Arguments {
  bool help = false;
  std::string file;                  // host or deploy file
  std::string processes;             // --process: the deploy file's processes to host
  std::vector<std::string> plugins;  // --plugin: loaded before the file's own
};

void usage(std::ostream& out) {
  out << "usage: wbi_host FILE.yaml [--plugin NAME|PATH]...\n"
         "       wbi_host DEPLOY.yaml --process NAME[,NAME...] [--plugin NAME|PATH]...\n"
         "       wbi_host --help [--plugin NAME|PATH]...\n"
         "Runs the components listed in FILE.yaml (or those of process NAME of a deploy\n"
         "file; of several processes, in the order named) in one process until\n"
         "SIGINT/SIGTERM. Their types come from plugins: the built-in one, the --plugin\n"
         "ones, then the file's `plugins:` (a name is looked for as libNAME.so in\n"
         "$WBI_PLUGIN_PATH, the file's folder, then wbi's own plugin folder).\n";
}

// Throws std::invalid_argument for a bad command line.
Arguments parse(int argc, char** argv) {
  Arguments arguments;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&](const char* flag) -> std::string {
      if (i + 1 >= argc) {
        throw std::invalid_argument(std::string(flag) + " needs a value");
      }
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      arguments.help = true;
    } else if (arg == "--process") {
      arguments.processes = value("--process");
    } else if (arg == "--plugin") {
      arguments.plugins.push_back(value("--plugin"));
    } else if (!arg.empty() && arg[0] != '-' && arguments.file.empty()) {
      arguments.file = arg;
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (!arguments.help && arguments.file.empty()) {
    throw std::invalid_argument("no host or deploy file named");
  }
  return arguments;
}

int configuration_error(const std::exception& error) {
  wbi::runtime::print_line(stderr, std::string("wbi_host: configuration error: ") + error.what());
  return wbi::runtime::kExitConfigurationError;
}

// What `wbi_host FILE [--process NAMES]` hosts, and how it joins DDS.
struct HostInput {
  YAML::Node document;
  wbi::runtime::PlacementReader placement;
};

HostInput host_input(const std::string& file, const std::string& processes) {
  if (processes.empty()) {
    // A host file: the runtime reads it; its network and security blocks are
    // the deploy format's (the key check accepts the keys that reader reads).
    return {wbi::runtime::read_host_file(file),
            {{wbi::deploy::kPlacementKeys.begin(), wbi::deploy::kPlacementKeys.end()},
             wbi::deploy::read_placement}};
  }
  // Processes of a deploy file: its reader has read and checked every key; the
  // runtime gets their components, and the file's join keys as join options.
  wbi::deploy::ProcessHost host = wbi::deploy::load_process_host(file, processes);
  return {host.document,
          {{},
           [join = std::move(host.join)](const YAML::Node&, const std::string&,
                                         const std::string& identity,
                                         wbi::dds::ParticipantOptions& options) {
             wbi::deploy::apply_join_keys(join, identity, options);
           }}};
}

}  // namespace

int main(int argc, char** argv) {
  Arguments arguments;
  try {
    arguments = parse(argc, argv);
  } catch (const std::invalid_argument& error) {
    std::cerr << "wbi_host: " << error.what() << "\n";
    usage(std::cerr);
    return wbi::runtime::kExitConfigurationError;
  }
  // Declared first: it outlives every component made from it.
  wbi::Catalog catalog;
  if (arguments.help) {
    usage(std::cout);
    try {
      wbi::runtime::load_plugins(catalog, arguments.plugins);
    } catch (const std::exception& error) {
      std::cerr << "wbi_host: " << error.what() << "\n";
      return 1;
    }
    std::cout << "\n"
              << wbi::runtime::describe_catalog(catalog)
              << "(and `hold`, every controller host's own fallback)\n";
    return 0;
  }
  // Started by `wbi launch`: its death (even SIGKILL) is a SIGTERM here, taken
  // by sigwait below like any other, so the components stop in order.
  wbi::launch::stop_when_launcher_dies();
  // Signals are taken by sigwait below; blocked before any thread starts so
  // that no DDS or loop thread receives them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  // A component that ends the process (its run is over, or a fault): stop the
  // components as SIGTERM does, then exit with its code.
  wbi::runtime::set_process_exit_handler([](int) { ::kill(::getpid(), SIGTERM); });
  const std::string& file = arguments.file;
  const bool from_deploy = !arguments.processes.empty();
  // Reading the file, loading the plugins and making the components: any
  // error here is the configuration's (respawning cannot fix it).
  std::unique_ptr<wbi::runtime::Host> made;
  try {
    const HostInput input = host_input(file, arguments.processes);
    std::vector<std::string> plugins = arguments.plugins;
    for (auto& plugin : wbi::runtime::plugins_of(input.document, file)) {
      plugins.push_back(std::move(plugin));
    }
    wbi::runtime::load_plugins(catalog, plugins, std::filesystem::path(file).parent_path());
    made = std::make_unique<wbi::runtime::Host>(
        input.document, file, from_deploy ? arguments.processes : "",
        catalog.registry<wbi::runtime::Registry>(), input.placement);
  } catch (const std::exception& error) {
    return configuration_error(error);
  }
  wbi::runtime::Host& host = *made;
  // Secured: a handshake that stalls while this process starts ends it with
  // kExitStartStalled; `wbi launch` starts it again (no component has run yet).
  wbi::runtime::HandshakeWatch handshakes(host.participant(), [](const std::string& why) {
    wbi::runtime::print_line(
        stderr, "wbi_host: start-up stalled: " + why + ": ending with exit code " +
                    std::to_string(wbi::runtime::kExitStartStalled) + " to be started again");
    std::fflush(nullptr);
    std::_Exit(wbi::runtime::kExitStartStalled);
  });
  try {
    host.start();
    handshakes.started();
    // The components already run and print: this line goes out whole (console_line.hpp).
    wbi::runtime::print_line(stdout, "wbi_host: running " + std::to_string(host.size()) +
                                         " component(s) from " + file + " on domain " +
                                         std::to_string(host.participant().domain_id()));
    int signal_number = 0;
    sigwait(&signals, &signal_number);
    const auto errors = host.stop();
    for (const auto& error : errors) {
      wbi::runtime::print_line(stderr, "wbi_host: " + error);
    }
    const auto requested = wbi::runtime::requested_process_exit_code();
    const std::string why =
        requested ? "a component ended the process, exit code " + std::to_string(*requested)
                  : (signal_number == SIGINT ? "SIGINT" : "SIGTERM");
    wbi::runtime::print_line(stdout, "wbi_host: stopped (" + why + ")");
    if (!errors.empty()) {
      return 1;
    }
    if (requested) {
      return *requested;
    }
    return signal_number == SIGINT ? 130 : 0;
  } catch (const wbi::runtime::ConfigurationError& error) {
    return configuration_error(error);
  } catch (const wbi::runtime::ParameterError& error) {
    return configuration_error(error);
  } catch (const std::exception& error) {
    wbi::runtime::print_line(stderr, std::string("wbi_host: ") + error.what());
    return 1;
  }
}
