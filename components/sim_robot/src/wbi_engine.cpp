// The "wbi" engine: the project's own plant, built from its configuration file.
#include <wbi/robot_config/robot_config.hpp>
#include <wbi/sim/sim_backend.hpp>

#include "engines.hpp"

namespace wbi::sim_robot {

std::unique_ptr<actuation::SimulationBackend> make_wbi_engine(const EngineContext& context) {
  return std::make_unique<sim::SimBackend>(
      robot_config::load_robot_config(context.config.string()));
}

}  // namespace wbi::sim_robot
