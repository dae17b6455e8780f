#include "wbi/actuation/simulation_backend.hpp"

#include <stdexcept>
#include <string>

namespace wbi::actuation {

void SimulationBackend::step() {
  if (state() != LifecycleState::inactive && state() != LifecycleState::active) {
    throw std::logic_error(std::string("simulation backend: step() needs configure() first (the "
                                       "backend is ") +
                           to_string(state()) + ")");
  }
  on_step();
}

}  // namespace wbi::actuation
