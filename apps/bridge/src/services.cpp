#include "services.hpp"

#include <nlohmann/json.hpp>
#include <wbi/controllers/host_client.hpp>

namespace wbi::bridge {

namespace {

using nlohmann::json;

const char* kListRequest = R"({"type":"object","properties":{}})";
const char* kListResponse =
    R"({"type":"object","properties":{"controllers":{"type":"array","items":{"type":"object","properties":{"name":{"type":"string"},"type":{"type":"string"},"active":{"type":"boolean"},"configure_error":{"type":"string"}}}}}})";
const char* kSwitchRequest =
    R"({"type":"object","properties":{"activate":{"type":"string"},"deactivate":{"type":"string"}}})";
const char* kSwitchResponse = R"({"type":"object","properties":{"result":{"type":"string"}}})";

std::string text_field(const json& request, const char* key) {
  if (!request.contains(key)) {
    return {};
  }
  if (!request[key].is_string()) {
    throw std::invalid_argument(std::string("'") + key +
                                "' must be a string (a controller's name)");
  }
  return request[key].get<std::string>();
}

}  // namespace

std::vector<protocol::Service> Services::add_robot(const std::string& robot) {
  std::lock_guard lock(mutex_);
  for (const auto& [id, entry] : services_) {
    if (entry.robot == robot) {
      return {};
    }
  }
  const auto next = static_cast<std::uint32_t>(services_.size() + 1);
  const protocol::Service list{
      next,         "/" + robot + "/controllers/list", "wbi.ListControllers", "json", kListRequest,
      kListResponse};
  const protocol::Service change{next + 1,
                                 "/" + robot + "/controllers/switch",
                                 "wbi.SwitchControllers",
                                 "json",
                                 kSwitchRequest,
                                 kSwitchResponse};
  services_[list.id] = {list, robot, false};
  services_[change.id] = {change, robot, true};
  return {list, change};
}

std::vector<protocol::Service> Services::all() const {
  std::lock_guard lock(mutex_);
  std::vector<protocol::Service> out;
  for (const auto& [id, entry] : services_) {
    out.push_back(entry.service);
  }
  return out;
}

void Services::call(ClientId client, const protocol::ServiceCallRequest& request) {
  const auto fail = [this, client, &request](const std::string& why) {
    server_.send(client, OutgoingMessage::json(protocol::service_call_failure(
                             request.service_id, request.call_id, why)));
  };
  Entry entry;
  {
    std::lock_guard lock(mutex_);
    const auto found = services_.find(request.service_id);
    if (found == services_.end()) {
      fail("no service " + std::to_string(request.service_id));
      return;
    }
    entry = found->second;
  }
  if (request.encoding != "json") {
    fail(entry.service.name + ": requests are json, not '" + request.encoding + "'");
    return;
  }
  json body = json::parse(request.payload.begin(), request.payload.end(), nullptr, false);
  if (body.is_discarded() || !body.is_object()) {
    fail(entry.service.name + ": the request is not a JSON object");
    return;
  }
  const auto service_id = request.service_id;
  const auto call_id = request.call_id;
  hosts_.run(entry.robot, [this, client, entry, body, service_id,
                           call_id](controllers::HostClient& host) {
    json response;
    try {
      if (entry.switch_call) {
        response["result"] =
            host.switch_controllers(text_field(body, "activate"), text_field(body, "deactivate"));
      } else {
        response["controllers"] = json::array();
        for (const auto& controller : host.list()) {
          response["controllers"].push_back({{"name", controller.name},
                                             {"type", controller.type},
                                             {"active", controller.active},
                                             {"configure_error", controller.configure_error}});
        }
      }
    } catch (const std::exception& error) {
      server_.send(client, OutgoingMessage::json(protocol::service_call_failure(
                               service_id, call_id, entry.service.name + ": " + error.what())));
      return;
    }
    const std::string text = response.dump();
    server_.send(client,
                 OutgoingMessage::binary(protocol::service_call_response(
                     service_id, call_id, "json",
                     std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()))));
  });
}

}  // namespace wbi::bridge
