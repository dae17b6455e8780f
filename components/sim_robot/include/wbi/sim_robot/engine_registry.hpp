// Simulation engines by name, for the sim_robot component's `engine` parameter.
// An engine is a factory of SimulationBackend (wbi/actuation/simulation_backend.hpp):
// the robot loop, the DDS sides, lockstep and the ground truth are the robot
// driver's (wbi/robot/robot_driver.hpp), the same for every engine. Adding an
// engine is one registration: EngineRegistry::add in a plugin (wbi/plugin.hpp;
// the project's own in src/builtin_engines.cpp); no loop code changes.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <wbi/actuation/simulation_backend.hpp>
#include <wbi/registry.hpp>
#include <wbi/runtime/parameters.hpp>

namespace wbi::sim_robot {

// What an engine is built from.
struct EngineContext {
  std::string robot;             // the robot's name (topics wbi/<robot>/…)
  std::filesystem::path config;  // the `config` parameter, a relative path resolved
                                 // against the folder of the host (or deploy) file
  // The component's parameters: an engine may read keys of its own (every key
  // nobody reads is rejected after configure).
  const runtime::Parameters& parameters;
};

// An engine's factory builds the backend, UNCONFIGURED (the driver configures
// and activates it). Bad input: throw with a message naming the file and key.
using EngineFactory =
    std::function<std::unique_ptr<actuation::SimulationBackend>(const EngineContext&)>;

class EngineRegistry : public Registry<actuation::SimulationBackend, const EngineContext&> {
 public:
  static constexpr const char* kKind = "engine";  // its name in a wbi::Catalog
  EngineRegistry() : Registry("engine") {}
};

// The engines built into wbi::sim_robot: "wbi" (the project's own plant,
// wbi::sim) and, when built with it, "mujoco".
void register_builtin_engines(EngineRegistry& engines);
EngineRegistry builtin_engines();  // a registry with just those

}  // namespace wbi::sim_robot
