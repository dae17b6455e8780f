#include "wbi/sim_robot/sim_robot.hpp"

#include <filesystem>
#include <memory>
#include <string>

#include <wbi/robot/robot_driver.hpp>

namespace wbi::sim_robot {

namespace {

// A relative `config` is looked up beside the host (or deploy) file.
std::filesystem::path config_path(const runtime::Parameters& parameters) {
  auto path = std::filesystem::path(parameters.require<std::string>("config"));
  if (path.is_relative() && !parameters.file().empty() && parameters.file() != "<string>") {
    path = std::filesystem::path(parameters.file()).parent_path() / path;
  }
  return path;
}

}  // namespace

void register_components(runtime::Registry& registry,
                         std::shared_ptr<const EngineRegistry> engines) {
  robot::register_simulation(
      registry, "sim_robot",
      [engines](const runtime::Parameters& parameters) {
        const auto engine = parameters.get<std::string>("engine", "wbi");
        if (!engines->contains(engine)) {
          throw runtime::ParameterError(parameters.where("engine") + ": unknown engine '" + engine +
                                        "' (registered: " + engines->names_text() + ")");
        }
        const EngineContext context{parameters.require<std::string>("robot"),
                                    config_path(parameters), parameters};
        return engines->create(engine, context);
      },
      "simulated robot on an engine by name (`wbi plugins` lists them): sensor samples, ground "
      "truth and clock out, commands in");
}

void register_components(runtime::Registry& registry) {
  register_components(registry, std::make_shared<const EngineRegistry>(builtin_engines()));
}

}  // namespace wbi::sim_robot
