// The "mujoco" engine: MuJoCo (wbi::mujoco_sim::MujocoBackend), built from the
// robot config file (its mujoco: section). Compiled only with MuJoCo.
#include <wbi/mujoco_sim/mujoco_backend.hpp>

#include "engines.hpp"

namespace wbi::sim_robot {

std::unique_ptr<actuation::SimulationBackend> make_mujoco_engine(const EngineContext& context) {
  return std::make_unique<mujoco_sim::MujocoBackend>(load_engine_config(context));
}

}  // namespace wbi::sim_robot
