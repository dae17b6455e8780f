// The controller host on DDS: answers wbi/<robot>/controllers (list, switch,
// list and set parameters; idl/controllers.idl) and publishes the parameters'
// current values, latched, at start and after every change.
#pragma once

#include <array>
#include <mutex>
#include <string>

#include <wbi/msg/controllers.h>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/server.hpp>

#include "wbi/controllers/controller_host.hpp"

namespace wbi::controllers {

class HostService {
 public:
  HostService(dds::Participant& participant, const std::string& robot, const std::string& host_name,
              ControllerHost& host);
  // The parameters' current values on the latched topic.
  void publish_parameters();

 private:
  void handle(const msg::ControllerRequest& request, msg::ControllerReply& reply);
  void list_controllers(msg::ControllerReply& reply) const;
  void list_parameters(const std::string& controller,
                       decltype(msg::ControllerReply().parameters())& out) const;
  void set_parameter(const msg::ControllerRequest& request, msg::ControllerReply& reply);

  std::string robot_, host_name_;
  ControllerHost& host_;
  std::mutex publish_mutex_;
  std::uint64_t generation_ = 0;
  dds::Publisher<msg::ControllerParameters> parameters_;
  // A switch is not idempotent: a resent copy of an answered request gets the
  // same reply again (by client id and sequence number), not a second switch.
  std::array<msg::ControllerReply, 8> answered_{};
  std::size_t next_answered_ = 0;
  dds::Server<msg::ControllerRequest, msg::ControllerReply> server_;
};

}  // namespace wbi::controllers
