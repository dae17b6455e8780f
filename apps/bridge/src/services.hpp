// The protocol's services, per robot whose controller host is on the domain:
//   /<robot>/controllers/list    {}                                   → {"controllers": [...]}
//   /<robot>/controllers/switch  {"activate": NAME, "deactivate": NAME} → {"result": "..."}
// (`wbi controller list|switch`), requests and responses in JSON. Calls run
// on the hosts' worker (controller_hosts.hpp); a refusal or a host that does
// not answer is the protocol's serviceCallFailure with the host's line.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "controller_hosts.hpp"
#include "protocol.hpp"
#include "websocket_server.hpp"

namespace wbi::bridge {

class Services {
 public:
  Services(ControllerHosts& hosts, WebSocketServer& server) : hosts_(hosts), server_(server) {}

  // The services of a robot, the first time it is named; empty after.
  std::vector<protocol::Service> add_robot(const std::string& robot);
  std::vector<protocol::Service> all() const;
  // Answers `client` with a response or a failure, later, from the worker.
  void call(ClientId client, const protocol::ServiceCallRequest& request);

 private:
  struct Entry {
    protocol::Service service;
    std::string robot;
    bool switch_call = false;
  };

  ControllerHosts& hosts_;
  WebSocketServer& server_;
  mutable std::mutex mutex_;
  std::map<std::uint32_t, Entry> services_;
};

}  // namespace wbi::bridge
