#include "controller_client.hpp"

#include <chrono>

#include "../join_options.hpp"

namespace wbi::cli {

void add_controller_host_options(Options& options) {
  options.option("robot", "NAME", "the robot whose controller host to ask (required)");
  options.option("timeout", "SECONDS", "give up when the host does not answer within this time",
                 "5");
  add_join_options(options);
}

HostConnection::HostConnection(const Options& options, const std::string& verb) {
  if (!options.has("robot")) {
    throw UsageError("--robot NAME is required: the robot whose controller host to ask");
  }
  const auto timeout = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(options.get_double("timeout")));
  participant = std::make_unique<dds::Participant>(join_options(options, verb, ""));
  client = std::make_unique<controllers::HostClient>(*participant, options.get("robot"), timeout);
}

}  // namespace wbi::cli
