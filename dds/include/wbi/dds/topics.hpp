// Topic names. Every robot-specific topic carries the robot name, so several
// robots can share a domain: wbi/<robot>/<what>.
#pragma once

#include <string>
#include <string_view>

namespace wbi::dds::topics {

inline std::string robot_topic(const std::string& robot, const char* what) {
  return "wbi/" + robot + "/" + what;
}

inline std::string description(const std::string& robot) {
  return robot_topic(robot, "description");
}
inline std::string sensors(const std::string& robot) { return robot_topic(robot, "sensors"); }
inline std::string ground_truth(const std::string& robot) {
  return robot_topic(robot, "ground_truth");
}
inline std::string commands(const std::string& robot) { return robot_topic(robot, "commands"); }
inline std::string control_parameters(const std::string& robot) {
  return robot_topic(robot, "control_parameters");
}
inline std::string state(const std::string& robot) { return robot_topic(robot, "state"); }
inline std::string estimator_parameters(const std::string& robot) {
  return robot_topic(robot, "state/parameters");
}
// The model service of a robot (request/reply, see rpc.hpp): its topics are
// model_request(robot) and model_reply(robot).
inline std::string model_service(const std::string& robot) { return robot_topic(robot, "model"); }
// The model service's own description: the joint order of its model, which
// may differ from the robot's (wbi/<robot>/description, sent by the robot).
inline std::string model_description(const std::string& robot) {
  return robot_topic(robot, "model/description");
}
inline std::string model_request(const std::string& robot) {
  return robot_topic(robot, "model/request");
}
inline std::string model_reply(const std::string& robot) {
  return robot_topic(robot, "model/reply");
}

// The joint claims of a robot (request/reply, see rpc.hpp and idl/claims.idl)
// and its current owners (wbi::msg::JointOwners, latched).
inline std::string claim_service(const std::string& robot) { return robot_topic(robot, "claims"); }
inline std::string joint_owners(const std::string& robot) {
  return robot_topic(robot, "claims/owners");
}

// The controller host of a robot (request/reply, idl/controllers.idl) and its
// parameters' current values (wbi::msg::ControllerParameters, latched).
inline std::string controller_service(const std::string& robot) {
  return robot_topic(robot, "controllers");
}
inline std::string controller_parameters(const std::string& robot) {
  return robot_topic(robot, "controllers/parameters");
}

// A controller's named signals (wbi::msg::Signals): wbi/<robot>/signals/<controller>.
inline std::string signals(const std::string& robot, const std::string& controller) {
  return "wbi/" + robot + "/signals/" + controller;
}

// A controller's reference input (wbi::msg::TrajectoryPoint):
// wbi/<robot>/references/<controller>/<input>.
inline std::string reference(const std::string& robot, const std::string& controller,
                             const std::string& input) {
  return "wbi/" + robot + "/references/" + controller + "/" + input;
}

// The streams of which a robot has one producer: its description, sensors and
// ground truth, its estimator's state, its model service's description.
// Readers of them take one writer's samples (producers.hpp).
inline bool is_single_producer_stream(const std::string& topic) {
  if (topic.rfind("wbi/", 0) != 0) {
    return false;
  }
  const auto robot_end = topic.find('/', 4);
  if (robot_end == std::string::npos || robot_end == 4) {
    return false;
  }
  const std::string_view what = std::string_view(topic).substr(robot_end + 1);
  return what == "description" || what == "sensors" || what == "ground_truth" || what == "state" ||
         what == "model/description";
}

inline const char* kStatus = "wbi/status";
inline const char* kClock = "wbi/clock";
// What happened in a run, one topic per domain (idl/events.idl, docs/events.md).
inline const char* kEvents = "wbi/events";

}  // namespace wbi::dds::topics
