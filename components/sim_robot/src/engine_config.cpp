// The robot config an engine simulates: the `config` file, plus the scenario
// the deploy file adds to it (a push), so that one robot file serves every
// experiment.
#include <string>
#include <vector>

#include <wbi/model/urdf.hpp>
#include <wbi/robot_config/robot_config.hpp>

#include "engines.hpp"

namespace wbi::sim_robot {

namespace {

Eigen::Vector3d vector3(const runtime::Parameters& parameters, const std::string& key,
                        const std::vector<double>& fallback) {
  const auto v = parameters.get<std::vector<double>>(key, fallback);
  if (v.size() != 3) {
    throw runtime::ParameterError(parameters.where(key) + ": " + key +
                                  ": expected 3 numbers [x, y, z], got " +
                                  std::to_string(v.size()));
  }
  return {v[0], v[1], v[2]};
}

// push_link, push_force, push_start_s, push_duration_s, push_point: one more
// entry of the config's `pushes:` (robot_side/robot_config/README.md).
void add_push(const runtime::Parameters& parameters, robot_config::RobotConfig& config) {
  const bool any = parameters.has("push_link") || parameters.has("push_force") ||
                   parameters.has("push_start_s") || parameters.has("push_duration_s") ||
                   parameters.has("push_point");
  if (!any) {
    return;
  }
  robot_config::PushConfig push;
  push.link = parameters.require<std::string>("push_link");
  for (const char* key : {"push_force", "push_start_s"}) {
    if (!parameters.has(key)) {
      throw runtime::ParameterError(parameters.where("push_link") + ": " + key +
                                    ": missing (a push needs push_link, push_force and "
                                    "push_start_s)");
    }
  }
  push.force = vector3(parameters, "push_force", {});
  push.point = vector3(parameters, "push_point", {0.0, 0.0, 0.0});
  push.start = parameters.get<double>("push_start_s", 0.0);
  push.duration = parameters.get<double>("push_duration_s", push.duration);
  if (!(push.start >= 0.0)) {
    throw runtime::ParameterError(parameters.where("push_start_s") +
                                  ": push_start_s: must be >= 0 [s]");
  }
  if (!(push.duration > 0.0)) {
    throw runtime::ParameterError(parameters.where("push_duration_s") +
                                  ": push_duration_s: must be > 0 [s]");
  }
  if (!model::load_urdf_file(config.urdf).has_frame(push.link)) {
    throw runtime::ParameterError(parameters.where("push_link") +
                                  ": push_link: unknown link or frame '" + push.link + "' in " +
                                  config.urdf);
  }
  config.pushes.push_back(push);
}

}  // namespace

robot_config::RobotConfig load_engine_config(const EngineContext& context) {
  auto config = robot_config::load_robot_config(context.config.string());
  add_push(context.parameters, config);
  return config;
}

}  // namespace wbi::sim_robot
