// Internal: the factories of the engines built into wbi::sim_robot, one file each.
#pragma once

#include <memory>

#include "wbi/sim_robot/engine_registry.hpp"

namespace wbi::sim_robot {

// "wbi": the project's own plant (wbi::sim::SimBackend) from its YAML (context.config).
std::unique_ptr<actuation::SimulationBackend> make_wbi_engine(const EngineContext& context);

#ifdef WBI_WITH_MUJOCO
// "mujoco": MuJoCo (wbi::mujoco_sim::MujocoBackend) from the same robot config.
std::unique_ptr<actuation::SimulationBackend> make_mujoco_engine(const EngineContext& context);
#endif

}  // namespace wbi::sim_robot
