// What `wbi controller` and `wbi param` share: the robot's controller host,
// reached through controllers::HostClient. Without --robot, the only robot
// with a controller host on the domain (cli/README.md, "Which robot").
#pragma once

#include <memory>
#include <string>

#include <wbi/controllers/host_client.hpp>
#include <wbi/dds/participant.hpp>

#include "../options.hpp"

namespace wbi::cli {

// The notes of `wbi controller --help` and `wbi param --help`.
inline constexpr const char* kWhichRobotNote =
    "Without --robot they ask the only robot with a controller host on the domain\n"
    "(named on stderr); with several, the error lists them.\n";

// Declares --robot and --timeout, and the join options.
void add_controller_host_options(Options& options);

// The participant and the client of the robot named by --robot, or of the only
// robot whose controller host discovery finds within --timeout (named on
// stderr). None found, or several, is an error naming them.
struct HostConnection {
  HostConnection(const Options& options, const std::string& verb);
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<controllers::HostClient> client;
};

}  // namespace wbi::cli
