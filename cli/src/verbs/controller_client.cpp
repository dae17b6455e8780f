#include "controller_client.hpp"

#include <chrono>

#include <wbi/dds/client.hpp>
#include <wbi/dds/topics.hpp>

#include "../join_options.hpp"

namespace wbi::cli {

void add_controller_host_options(Options& options) {
  options.option("robot", "NAME", "the robot whose controller host to ask (required)");
  options.option("timeout", "SECONDS", "give up when the host does not answer within this time",
                 "5");
  add_join_options(options);
}

msg::ControllerReply call_controller_host(const Options& options, msg::ControllerRequest request,
                                          const std::string& verb) {
  if (!options.has("robot")) {
    throw UsageError("--robot NAME is required: the robot whose controller host to ask");
  }
  const std::string robot = options.get("robot");
  const auto timeout = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(options.get_double("timeout")));
  dds::Participant participant(join_options(options, verb, ""));
  dds::Client<msg::ControllerRequest, msg::ControllerReply> client(
      participant, dds::topics::controller_service(robot));
  request.robot(robot);
  msg::ControllerReply reply;
  client.call(request, reply, timeout);
  return reply;
}

}  // namespace wbi::cli
