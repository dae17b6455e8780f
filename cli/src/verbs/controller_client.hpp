// What `wbi controller` and `wbi param` share: the robot's controller host,
// reached over its service wbi/<robot>/controllers (idl/controllers.idl).
#pragma once

#include <string>

#include <wbi/msg/controllers.h>

#include "../options.hpp"

namespace wbi::cli {

// Declares --robot and --timeout, and the join options.
void add_controller_host_options(Options& options);
// One call to the host. Throws std::runtime_error naming the service when no
// host answers; a refusal comes back in reply.error().
msg::ControllerReply call_controller_host(const Options& options, msg::ControllerRequest request,
                                          const std::string& verb);

}  // namespace wbi::cli
