// Internal: the factories of the engines built into wbi::sim_robot, one file each.
#pragma once

#include <memory>

#include <wbi/robot_config/robot_config.hpp>

#include "wbi/sim_robot/engine_registry.hpp"

namespace wbi::sim_robot {

// The `config` file with the deploy file's push (push_link, push_force,
// push_start_s, push_duration_s, push_point) added to its pushes.
robot_config::RobotConfig load_engine_config(const EngineContext& context);

// "wbi": the project's own plant (wbi::sim::SimBackend) from its YAML (context.config).
std::unique_ptr<actuation::SimulationBackend> make_wbi_engine(const EngineContext& context);

#ifdef WBI_WITH_MUJOCO
// "mujoco": MuJoCo (wbi::mujoco_sim::MujocoBackend) from the same robot config.
std::unique_ptr<actuation::SimulationBackend> make_mujoco_engine(const EngineContext& context);
#endif

}  // namespace wbi::sim_robot
