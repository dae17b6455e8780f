// The "wbi" engine: the project's own plant, built from its configuration file.
#include <wbi/sim/sim_backend.hpp>

#include "engines.hpp"

namespace wbi::sim_robot {

std::unique_ptr<actuation::SimulationBackend> make_wbi_engine(const EngineContext& context) {
  return std::make_unique<sim::SimBackend>(load_engine_config(context));
}

}  // namespace wbi::sim_robot
