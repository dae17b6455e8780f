#include "host_service.hpp"

#include <chrono>

#include <wbi/dds/topics.hpp>

namespace wbi::controllers {

namespace {
dds::ServerOptions server_options() {
  dds::ServerOptions options;
  options.handle_on_dds_thread = false;  // a switch waits for the loop's next tick
  return options;
}
}  // namespace

HostService::HostService(dds::Participant& participant, const std::string& robot,
                         const std::string& host_name, ControllerHost& host)
    : robot_(robot),
      host_name_(host_name),
      host_(host),
      parameters_(participant, dds::topics::controller_parameters(robot), dds::qos::kLatched),
      server_(
          participant, dds::topics::controller_service(robot),
          [this](const msg::ControllerRequest& request, msg::ControllerReply& reply) {
            handle(request, reply);
          },
          server_options()) {}

void HostService::handle(const msg::ControllerRequest& request, msg::ControllerReply& reply) {
  for (const auto& answered : answered_) {
    if (answered.seq() == request.seq() &&
        answered.client_id().to_string() == request.client_id().to_string()) {
      reply = answered;  // a resent copy: the reply again, not the action again
      return;
    }
  }
  reply.error("");
  reply.text("");
  if (request.robot().to_string() != robot_) {
    reply.error("this host controls robot '" + robot_ + "', not '" + request.robot().to_string() +
                "'");
  } else {
    switch (request.action()) {
      case msg::ControllerAction::LIST_CONTROLLERS:
        list_controllers(reply);
        break;
      case msg::ControllerAction::SWITCH_CONTROLLERS: {
        std::vector<std::string> activate, deactivate;
        for (const auto& name : request.activate()) {
          activate.push_back(name.to_string());
        }
        for (const auto& name : request.deactivate()) {
          deactivate.push_back(name.to_string());
        }
        const SwitchResult result = host_.request_switch(activate, deactivate);
        (result.done ? reply.text(result.text) : reply.error(result.text));
        reply.torque_step(result.torque_step);
        list_controllers(reply);
        break;
      }
      case msg::ControllerAction::LIST_PARAMETERS:
        list_parameters(request.controller().to_string(), reply.parameters());
        break;
      case msg::ControllerAction::SET_PARAMETER:
        set_parameter(request, reply);
        break;
    }
  }
  reply.client_id(request.client_id());
  reply.seq(request.seq());
  answered_[next_answered_] = reply;
  next_answered_ = (next_answered_ + 1) % answered_.size();
}

void HostService::list_controllers(msg::ControllerReply& reply) const {
  reply.controllers().clear();
  for (const auto& info : host_.list()) {
    msg::HostedController entry;
    entry.name(info.name);
    entry.type(info.type);
    entry.active(info.active);
    entry.configure_error(info.configure_error);
    reply.controllers().push_back(entry);
  }
}

void HostService::list_parameters(const std::string& controller,
                                  decltype(msg::ControllerReply().parameters())& out) const {
  out.clear();
  for (const auto& info : host_.list()) {
    if (!controller.empty() && info.name != controller) {
      continue;
    }
    const ParameterTable& table = host_.parameters(info.name);
    for (std::size_t i = 0; i < table.size(); ++i) {
      const ParameterSpec& spec = table.spec(i);
      msg::ControllerParameter entry;
      entry.controller(info.name);
      entry.name(spec.name);
      entry.unit(spec.unit);
      entry.help(spec.help);
      entry.min(spec.min);
      entry.max(spec.max);
      entry.live(spec.live);
      entry.values(table.snapshot(i));
      entry.is_text(spec.text);
      entry.text(table.text(i));
      out.push_back(entry);
    }
  }
  if (!controller.empty() && out.empty()) {
    (void)host_.parameters(controller);  // throws naming the hosted controllers
  }
}

void HostService::set_parameter(const msg::ControllerRequest& request,
                                msg::ControllerReply& reply) {
  const std::string controller = request.controller().to_string();
  const std::string parameter = request.parameter().to_string();
  const ParameterTable& table = host_.parameters(controller);
  const std::uint64_t before = table.generation();
  if (table.spec(table.index(parameter)).text) {
    reply.error(controller + ": " + parameter +
                " is a text read at configure (e.g. a frame name): change it in the deploy file");
    return;
  }
  host_.set_parameter(controller, parameter,
                      std::vector<double>(request.values().begin(), request.values().end()));
  // Applied between two ticks: answer (and publish) once it is.
  if (!host_.wait_for_parameters(controller, before, std::chrono::seconds(2))) {
    reply.error(controller + "." + parameter +
                ": accepted but not applied within 2 s: is the host's loop running?");
    return;
  }
  const std::size_t index = table.index(parameter);
  reply.text(controller + "." + parameter + " = " + format_values(table.snapshot(index)) +
             (table.spec(index).unit.empty() ? "" : " " + table.spec(index).unit));
  publish_parameters();
}

void HostService::publish_parameters() {
  std::lock_guard lock(publish_mutex_);
  msg::ControllerParameters sample;
  sample.header().robot(robot_);
  sample.header().stamp_ns(std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count());
  sample.header().seq(generation_);
  sample.host(host_name_);
  sample.generation(generation_++);
  list_parameters("", sample.parameters());
  parameters_.publish(sample);
}

}  // namespace wbi::controllers
