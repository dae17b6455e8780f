#include "wbi/controllers/host_client.hpp"

#include <wbi/dds/topics.hpp>
#include <wbi/types.hpp>

namespace wbi::controllers {

HostClient::HostClient(dds::Participant& participant, std::string robot,
                       std::chrono::nanoseconds timeout)
    : robot_(std::move(robot)),
      timeout_(timeout),
      client_(participant, dds::topics::controller_service(robot_)) {}

msg::ControllerReply HostClient::call(msg::ControllerRequest& request) {
  request.robot(robot_);
  msg::ControllerReply reply;
  client_.call(request, reply, timeout_);
  if (!reply.error().to_string().empty()) {
    throw Error(reply.error().to_string());
  }
  return reply;
}

std::vector<HostedControllerInfo> HostClient::list() {
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::LIST_CONTROLLERS);
  const msg::ControllerReply reply = call(request);  // outlives the loop over its entries
  std::vector<HostedControllerInfo> out;
  for (const auto& entry : reply.controllers()) {
    out.push_back({entry.name().to_string(), entry.type().to_string(), entry.active(),
                   entry.configure_error().to_string()});
  }
  return out;
}

std::string HostClient::switch_controllers(const std::string& activate,
                                           const std::string& deactivate) {
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::SWITCH_CONTROLLERS);
  if (!activate.empty()) {
    request.activate().push_back(activate);
  }
  if (!deactivate.empty()) {
    request.deactivate().push_back(deactivate);
  }
  return call(request).text().to_string();
}

std::vector<ParameterInfo> HostClient::parameters(const std::string& controller) {
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::LIST_PARAMETERS);
  request.controller(controller);
  const msg::ControllerReply reply = call(request);  // outlives the loop over its entries
  std::vector<ParameterInfo> out;
  for (const auto& entry : reply.parameters()) {
    ParameterInfo info;
    info.controller = entry.controller().to_string();
    info.name = entry.name().to_string();
    info.unit = entry.unit().to_string();
    info.help = entry.help().to_string();
    info.min = entry.min();
    info.max = entry.max();
    info.live = entry.live();
    info.is_text = entry.is_text();
    info.values = entry.values();
    info.text = entry.text().to_string();
    out.push_back(std::move(info));
  }
  return out;
}

std::string HostClient::set_parameter(const std::string& controller, const std::string& name,
                                      const std::vector<double>& values) {
  msg::ControllerRequest request;
  request.action(msg::ControllerAction::SET_PARAMETER);
  request.controller(controller);
  request.parameter(name);
  request.values(values);
  return call(request).text().to_string();
}

}  // namespace wbi::controllers
