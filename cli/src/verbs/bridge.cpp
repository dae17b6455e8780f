// `wbi bridge`: serves the deployment to Foxglove (or Lichtblick) over the
// Foxglove WebSocket protocol. The work is in wbi::bridge (tools/bridge);
// this file parses the command line, follows discovery and stops on Ctrl-C,
// SIGTERM or --duration.
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>

#include <wbi/bridge/bridge.hpp>

#include "../join_options.hpp"
#include "../options.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_bridge_signal(int /*signal*/) { stop_requested = true; }

std::vector<std::string> split_paths(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  std::string path;
  while (std::getline(in, path, ':')) {
    if (!path.empty()) {
      out.push_back(path);
    }
  }
  return out;
}

double positive(const Options& options, const std::string& name) {
  const double value = options.get_double(name);
  if (!(value > 0.0)) {
    throw UsageError("--" + name + " must be > 0");
  }
  return value;
}

bridge::BridgeOptions bridge_options(const Options& options) {
  bridge::BridgeOptions out;
  out.address = options.get("address");
  const long port = options.get_int("port");
  if (port < 0 || port > 65535) {
    throw UsageError("--port must be 0..65535 (0: any free port)");
  }
  out.port = static_cast<std::uint16_t>(port);
  out.robot = options.get_optional("robot").value_or("");
  out.urdf = options.get_optional("urdf").value_or("");
  out.mesh_paths = split_paths(options.get_optional("mesh-path").value_or(""));
  out.transforms_rate_hz = positive(options, "transforms-rate");
  out.transforms_from_ground_truth = options.has("ground-truth");
  out.allow_commands = options.has("allow-commands");
  out.client_queue_bytes = static_cast<std::size_t>(positive(options, "client-buffer") * 1e6);
  out.call_timeout = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(positive(options, "timeout")));
  return out;
}

}  // namespace

int run_bridge(Args args) {
  Options options(
      "wbi bridge [--address 127.0.0.1] [--port 8765] [options]",
      "Serves the deployment to Foxglove or Lichtblick (Foxglove WebSocket protocol,\n"
      "subprotocol foxglove.websocket.v1): open ws://ADDRESS:PORT in the app. Every wbi\n"
      "topic is a channel (CDR with its OMG IDL schema), wbi/<robot>/transforms moves\n"
      "the robot in the 3D panel (its URDF is the /robot_description parameter), and the\n"
      "hosted controllers' parameters can be read and set, controllers listed and switched\n"
      "(services), and references published to their inputs. A slow client loses its oldest\n"
      "messages and is told so; it never slows the robot or the other clients.\n"
      "See README.md, \"Watch a run live\". Runs until Ctrl-C, SIGTERM or --duration.");
  options.option("address", "IP",
                 "address to listen on (loopback by default: the bridge can steer the robot)",
                 "127.0.0.1");
  options.option("port", "PORT", "TCP port (0: any free port, printed)", "8765");
  options.option("robot", "NAME",
                 "only this robot's transforms and parameters (default: every robot)");
  options.option("urdf", "FILE",
                 "the robot's URDF, when its description's path is not readable here");
  options.option("mesh-path", "DIR[:DIR...]",
                 "folders fetchAsset serves meshes from (package://PKG/... "
                 "is looked up as DIR/PKG/... then DIR/...); the URDF's folder is always served");
  options.option("transforms-rate", "HZ", "at most this many transforms messages per second", "30");
  options.flag("ground-truth", "draw the simulation's ground truth instead of the state estimate");
  options.flag("allow-commands",
               "let clients publish raw actuator commands (wbi/<robot>/commands; "
               "each such client is logged); without it, only controllers' reference inputs");
  options.option("client-buffer", "MB",
                 "each client's send queue; a slow client loses its oldest "
                 "messages beyond it",
                 "8");
  options.option("timeout", "SECONDS", "how long a parameter set waits for the controller host",
                 "2");
  options.option("duration", "SECONDS", "stop after this long (0: until Ctrl-C)", "0");
  add_join_options(options);
  options.example("wbi bridge", "then open ws://127.0.0.1:8765 in Foxglove or Lichtblick");
  options.example("wbi bridge --robot arm --ground-truth",
                  "the arm only, drawn from the simulation's ground truth");
  if (!options.parse(args)) {
    return kExitOk;
  }
  const double duration_s = options.get_double("duration");
  if (duration_s < 0) {
    throw UsageError("--duration must be >= 0");
  }
  const auto settings = bridge_options(options);
  dds::Participant participant(join_options(options, "wbi bridge", ""));
  std::unique_ptr<bridge::Bridge> server;
  try {
    server = std::make_unique<bridge::Bridge>(participant, settings, [](const std::string& line) {
      std::cout << "wbi bridge: " << line << std::endl;
    });
  } catch (const std::runtime_error& error) {
    std::cerr << "wbi bridge: " << error.what() << "\n";
    return kExitError;
  }
  std::cout << "wbi bridge: listening on ws://" << settings.address << ":" << server->port()
            << " (domain " << participant.domain_id() << ")" << std::endl;
  std::signal(SIGINT, on_bridge_signal);
  std::signal(SIGTERM, on_bridge_signal);
  const auto start = std::chrono::steady_clock::now();
  while (!stop_requested) {
    server->discover();
    if (duration_s > 0 &&
        std::chrono::steady_clock::now() - start >= std::chrono::duration<double>(duration_s)) {
      break;
    }
    // Polls discovery and the stop flag; the data path runs on DDS and socket threads.
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  const auto counts = server->counts();
  std::cout << "wbi bridge: stopped; " << counts.forwarded << " messages forwarded, "
            << counts.channels << " channels" << std::endl;
  return kExitOk;
}

}  // namespace wbi::cli
