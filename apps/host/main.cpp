// wbi_host FILE.yaml: runs the components a host file lists (see
// wbi/runtime/host.hpp) in this process until SIGINT or SIGTERM, then stops
// them cleanly (deactivate, cleanup, shutdown, in reverse order); started by
// `wbi launch`, also when the launcher dies.
// Exit codes: 0 after SIGTERM, 130 after SIGINT, 1 on error (one line on stderr);
// a component that ends the process (wbi/runtime/process_exit.hpp) gives its code.
#include <csignal>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>

#include <pthread.h>

#include <wbi/dds/participant.hpp>
#include <wbi/deploy/placement.hpp>
#include <wbi/deploy/process_host.hpp>
#include <wbi/launch/launcher.hpp>
#include <wbi/runtime/builtin.hpp>
#include <wbi/runtime/console_line.hpp>
#include <wbi/runtime/host.hpp>
#include <wbi/runtime/process_exit.hpp>

#include "components.hpp"

namespace {

void usage(std::ostream& out, const wbi::runtime::Registry& registry) {
  out << "usage: wbi_host FILE.yaml\n"
         "       wbi_host DEPLOY.yaml --process NAME[,NAME...]\n"
         "Runs the components listed in FILE.yaml (or those of process NAME of a deploy\n"
         "file; of several processes, in the order named) in one process until\n"
         "SIGINT/SIGTERM.\n"
         "Component types:\n";
  for (const auto& type : registry.names()) {
    out << "  " << type << "  " << registry.description(type) << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  wbi::runtime::Registry registry;
  wbi::runtime::register_builtin_components(registry);
  wbi::host::register_components(registry);
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    usage(std::cout, registry);
    return 0;
  }
  const bool from_deploy = argc == 4 && std::strcmp(argv[2], "--process") == 0;
  if (argc != 2 && !from_deploy) {
    usage(std::cerr, registry);
    return 1;
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
  try {
    // The deploy reader turns the file's network and security blocks into join
    // options; the host file's key check accepts the keys it reads.
    const wbi::runtime::PlacementReader placement{
        {wbi::deploy::kPlacementKeys.begin(), wbi::deploy::kPlacementKeys.end()},
        wbi::deploy::read_placement};
    // One process of a deploy file: the deploy reader picks it out (the runtime
    // reads host documents only).
    auto host_ptr =
        from_deploy
            ? std::make_unique<wbi::runtime::Host>(wbi::deploy::load_process_host(argv[1], argv[3]),
                                                   argv[1], argv[3], registry, placement)
            : std::make_unique<wbi::runtime::Host>(argv[1], registry, placement);
    auto& host = *host_ptr;
    host.start();
    // The components already run and print: this line goes out whole (console_line.hpp).
    wbi::runtime::print_line(stdout, "wbi_host: running " + std::to_string(host.size()) +
                                         " component(s) from " + argv[1] + " on domain " +
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
  } catch (const std::exception& error) {
    wbi::runtime::print_line(stderr, std::string("wbi_host: ") + error.what());
    return 1;
  }
}
