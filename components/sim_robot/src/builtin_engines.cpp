// The engines built into wbi::sim_robot. A new engine is one add() here (and
// its factory in a file of its own, declared in engines.hpp).
#include "engines.hpp"

namespace wbi::sim_robot {

void register_builtin_engines(EngineRegistry& engines) {
  engines.add("wbi", make_wbi_engine,
              "the project's own plant: ABA, spring contacts (robot_side/sim/README.md)");
#ifdef WBI_WITH_MUJOCO
  engines.add("mujoco", make_mujoco_engine,
              "MuJoCo: soft constraint contacts, implicit integrator (robot_side/mujoco_sim)");
#endif
}

EngineRegistry builtin_engines() {
  EngineRegistry engines;
  register_builtin_engines(engines);
  return engines;
}

}  // namespace wbi::sim_robot
