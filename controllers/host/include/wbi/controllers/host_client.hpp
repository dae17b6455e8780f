// A client of a robot's controller host (wbi/<robot>/controllers,
// idl/controllers.idl), for tools and scripts: `wbi controller`, `wbi param`
// and Python's wbi.ControllerHost. One call at a time; each waits at most
// `timeout` and throws dds::CallError naming the service when no host answers.
// A refusal (an unknown name, a value out of range, …) is a wbi::Error with
// the host's one line.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include <wbi/msg/controllers.h>
#include <wbi/dds/client.hpp>

namespace wbi::controllers {

struct HostedControllerInfo {
  std::string name, type;
  bool active = false;
  std::string configure_error;  // empty when configured
};

struct ParameterInfo {
  std::string controller, name, unit, help;
  double min = 0.0, max = 0.0;
  bool live = false;
  bool is_text = false;
  std::vector<double> values;  // empty: unset, or a text parameter
  std::string text;
};

class HostClient {
 public:
  HostClient(dds::Participant& participant, std::string robot, std::chrono::nanoseconds timeout);

  std::vector<HostedControllerInfo> list();
  // "pd → hold at t = …; torque step …". activate / deactivate: "" for none.
  std::string switch_controllers(const std::string& activate, const std::string& deactivate);
  // controller "": every hosted controller's.
  std::vector<ParameterInfo> parameters(const std::string& controller);
  // "pd.gain_scale = 0.5", once the host applied it.
  std::string set_parameter(const std::string& controller, const std::string& name,
                            const std::vector<double>& values);

 private:
  msg::ControllerReply call(msg::ControllerRequest& request);

  std::string robot_;
  std::chrono::nanoseconds timeout_;
  dds::Client<msg::ControllerRequest, msg::ControllerReply> client_;
};

}  // namespace wbi::controllers
