// The plugin `lab_plugin` (liblab_plugin.so): what this lab adds to wbi. A
// deploy file loads it with `plugins: [lab_plugin]`; `wbi plugins lab_plugin`
// lists what it registers, each with this plugin as its provider.
#include <wbi/plugin.hpp>
#include <wbi/runtime/registry.hpp>

#include "lab_delayed_engine.hpp"
#include "lab_impedance.hpp"
#include "lab_posture.hpp"
#include "lab_posture_planner.hpp"

WBI_PLUGIN(catalog) {
  catalog.registry<wbi::controllers::ControllerRegistry>().add<lab::LabImpedance>(
      "lab_impedance", "joint impedance + gravity compensation about a planner's posture");

  catalog.registry<wbi::controllers::ControllerRegistry>().add<lab::LabPosture>(
      "lab_posture", "the planner's posture, chained to lab_impedance's input in its host");

  catalog.registry<wbi::runtime::Registry>().add<lab::LabPosturePlanner>(
      "lab_posture_planner",
      "a slow, smooth posture on a controller's reference input (wbi/<robot>/references/…)");

  // The engine wraps another one, made by name from the same registry: the
  // catalog's, which outlives every robot made from it (wbi/catalog.hpp).
  auto& engines = catalog.registry<wbi::sim_robot::EngineRegistry>();
  const wbi::sim_robot::EngineRegistry* all_engines = &engines;
  engines.add(
      "lab_delayed",
      [all_engines](const wbi::sim_robot::EngineContext& context) {
        return lab::make_delayed_engine(*all_engines, context);
      },
      "the 'wbi' engine with joint commands delayed by delay_ticks ticks");
}
