// The "wbi" engine: the project's own plant, built from its configuration file.
#include <wbi/sim/sim_backend.hpp>
#include <wbi/sim/sim_config.hpp>

#include "engines.hpp"

namespace wbi::sim_robot {

std::unique_ptr<actuation::SimulationBackend> make_wbi_engine(const EngineContext& context) {
  return std::make_unique<sim::SimBackend>(sim::load_sim_config_file(context.config.string()));
}

}  // namespace wbi::sim_robot
