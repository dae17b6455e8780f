#include "controller_client.hpp"

#include <chrono>
#include <iostream>
#include <stdexcept>

#include <wbi/controllers/host_discovery.hpp>

#include "../join_options.hpp"

namespace wbi::cli {

namespace {

// --robot, or the only robot with a controller host on the domain.
std::string robot_to_ask(const Options& options, const dds::Participant& participant,
                         std::chrono::nanoseconds timeout, const std::string& verb) {
  if (const auto robot = options.get_optional("robot")) {
    return *robot;
  }
  const auto robots = controllers::find_controller_hosts(participant, timeout);
  const std::string domain = "domain " + std::to_string(participant.domain_id());
  if (robots.empty()) {
    throw std::runtime_error("no controller host found on " + domain + " within " +
                             options.get("timeout") +
                             " s (is a deployment with a controller_host running, e.g. wbi launch "
                             "deploy/arm_controller_host.yaml? another domain: --domain ID)");
  }
  if (robots.size() > 1) {
    std::string names;
    for (const auto& robot : robots) {
      names += (names.empty() ? "" : ", ") + robot;
    }
    throw UsageError(std::to_string(robots.size()) + " robots have a controller host on " + domain +
                     " (" + names + "): give --robot NAME");
  }
  std::cerr << verb << ": using robot '" << robots.front()
            << "', the only one with a controller host on " << domain << "\n";
  return robots.front();
}

}  // namespace

void add_controller_host_options(Options& options) {
  options.option("robot", "NAME",
                 "the robot whose controller host to ask (default: the only robot with a "
                 "controller host on the domain)");
  options.option("timeout", "SECONDS",
                 "give up when no host is found, or the host does not answer, within this time",
                 "5");
  add_join_options(options);
}

HostConnection::HostConnection(const Options& options, const std::string& verb) {
  const auto timeout = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(options.get_double("timeout")));
  participant = std::make_unique<dds::Participant>(join_options(options, verb, ""));
  client = std::make_unique<controllers::HostClient>(
      *participant, robot_to_ask(options, *participant, timeout, verb), timeout);
}

}  // namespace wbi::cli
